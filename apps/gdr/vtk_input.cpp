#include "vtk_input.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "gdr/error.h"

#if defined(GDR_CLI_HAVE_VTK)
#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkExecutive.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataReader.h>
#include <vtkXMLPolyDataReader.h>

#include "vtkGDRConversion.h"
#endif

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

namespace {
// Reads with `reader`, turning VTK's error events into the message of an IoError.
template <class Reader>
vtkPolyData* read(Reader* reader, const std::string& path, std::string& error) {
  vtkNew<vtkCallbackCommand> on_error;
  on_error->SetClientData(&error);
  on_error->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
    auto* text = static_cast<std::string*>(client);
    if (text->empty() && call) *text = static_cast<const char*>(call);
  });
  reader->AddObserver(vtkCommand::ErrorEvent, on_error);
  reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, on_error);
  reader->SetFileName(path.c_str());
  reader->Update();
  return reader->GetOutput();
}
}  // namespace

Pslg read_vtk_pslg(const std::string& path, std::string& warning) {
  if (!std::filesystem::exists(path)) throw Error(Status::IoError, path + ": no such file");
  std::string error;
  vtkPolyData* data = nullptr;
  vtkNew<vtkXMLPolyDataReader> xml;
  vtkNew<vtkPolyDataReader> legacy;
  if (lower_extension(path) == ".vtp") {
    data = read(xml.Get(), path, error);
  } else {
    legacy->SetFileName(path.c_str());
    legacy->ReadAllScalarsOn();  // not only the first: BoundaryMarker and PointAttributes
    if (!legacy->IsFilePolyData())
      throw Error(Status::IoError, path + ": not legacy VTK polydata (gdr 2d reads lines and polygons)");
    data = read(legacy.Get(), path, error);
  }
  if (!error.empty()) {
    // VTK's text: "ERROR: In FILE, line N\nvtkClass (0x...): MESSAGE"
    const std::size_t at = error.find("): ");
    throw Error(Status::IoError, path + ": " + (at == std::string::npos ? error : error.substr(at + 3)));
  }
  Pslg pslg;
  double z = 0;
  vtkGDRConversion::ToPslg(data, nullptr, pslg, z, warning);
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
