// The VTK side of gdr's .vtp/.vtk input (vtk_input.h), built only with VTK as a module that
// gdr loads when such an input comes: linking VTK into gdr cost every run 25 ms of loading
// before main, more than Triangle's whole run on a 10k-point map.
#include <string>

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkExecutive.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataReader.h>
#include <vtkXMLPolyDataReader.h>

#include "gdr/pslg.h"
#include "vtkGDRConversion.h"

namespace {
// Reads with `reader`, turning VTK's error events into the message of an error.
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

// Reads `path` (XML .vtp, or legacy .vtk) into `out`. Returns false with `error` set (the
// message of an IoError); nothing is thrown across the module's boundary.
extern "C" __attribute__((visibility("default"))) bool gdr_cli_read_vtk_pslg(const char* path_c, bool xml_file,
                                                                             gdr::Pslg* out, std::string* warning,
                                                                             std::string* error) {
  try {
    const std::string path = path_c;
    vtkPolyData* data = nullptr;
    vtkNew<vtkXMLPolyDataReader> xml;
    vtkNew<vtkPolyDataReader> legacy;
    if (xml_file) {
      data = read(xml.Get(), path, *error);
    } else {
      legacy->SetFileName(path.c_str());
      legacy->ReadAllScalarsOn();  // not only the first: BoundaryMarker and PointAttributes
      if (!legacy->IsFilePolyData()) {
        *error = path + ": not legacy VTK polydata (gdr 2d reads lines and polygons)";
        return false;
      }
      data = read(legacy.Get(), path, *error);
    }
    if (!error->empty()) {
      // VTK's text: "ERROR: In FILE, line N\nvtkClass (0x...): MESSAGE"
      const std::size_t at = error->find("): ");
      *error = path + ": " + (at == std::string::npos ? *error : error->substr(at + 3));
      return false;
    }
    double z = 0;
    vtkGDRConversion::ToPslg(data, nullptr, *out, z, *warning);
    return true;
  } catch (const std::exception& e) {
    *error = std::string(path_c) + ": " + e.what();
    return false;
  }
}
