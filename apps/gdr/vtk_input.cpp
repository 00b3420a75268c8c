#include "vtk_input.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <vector>

#if defined(GDR_CLI_HAVE_VTK)
#include <dlfcn.h>
#endif

#include "gdr/error.h"

namespace gdr::cli {

namespace {
std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}
}  // namespace

bool is_vtk_polydata(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == ".vtp" || ext == ".vtk";
}

#if defined(GDR_CLI_HAVE_VTK)

// The VTK reader module (vtk_reader_module.cpp) beside gdr: build/lib next to build/bin, or
// wherever the loader's search path finds it.
Pslg read_vtk_pslg(const std::string& path, std::string& warning) {
  if (!std::filesystem::exists(path)) throw Error(Status::IoError, path + ": no such file");
  using Read = bool (*)(const char*, bool, Pslg*, std::string*, std::string*);
  static Read reader = nullptr;
  std::string tried;
  if (!reader) {
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    std::vector<std::string> candidates;
    if (!ec) {
      candidates.push_back((exe.parent_path() / "../lib/libgdr_vtk_reader.so").string());
      candidates.push_back((exe.parent_path() / "libgdr_vtk_reader.so").string());
    }
    candidates.push_back("libgdr_vtk_reader.so");
    for (const std::string& c : candidates) {
      if (void* handle = dlopen(c.c_str(), RTLD_NOW | RTLD_LOCAL)) {
        reader = reinterpret_cast<Read>(dlsym(handle, "gdr_cli_read_vtk_pslg"));
        if (reader) break;
      }
      const char* why = dlerror();
      tried += "\n  " + (why ? std::string(why) : c);  // dlerror names the file
    }
  }
  if (!reader)
    throw Error(Status::IoError, path + ": gdr cannot load its VTK reader (libgdr_vtk_reader.so), which reading "
                                        ".vtp and .vtk needs; tried:" + tried);
  Pslg pslg;
  std::string error;
  if (!reader(path.c_str(), lower_extension(path) == ".vtp", &pslg, &warning, &error)) throw Error(Status::IoError, error);
  return pslg;
}

#else

Pslg read_vtk_pslg(const std::string& path, std::string&) {
  throw Error(Status::IoError, path + ": this gdr was built without VTK, which reading .vtp and "
                                      ".vtk needs (configure with ParaView's development files, or "
                                      "convert the input to Triangle's .poly)");
}

#endif

}  // namespace gdr::cli
