// What the VTK filter tests share: CHECK (counts failures and goes on), EventLog (a filter's
// error and warning events), and RunNamedTest (main: runs the test named on the command line).
#pragma once

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkObject.h"

#include <algorithm>
#include <functional>
#include <iostream>
#include <map>
#include <string>
#include <vector>

namespace gdr_test
{
inline int Failures = 0;

#define CHECK(cond)                                                                           \
  do                                                                                          \
  {                                                                                           \
    if (!(cond))                                                                              \
    {                                                                                         \
      std::cerr << __FILE__ << ":" << __LINE__ << ": check failed: " #cond << std::endl;      \
      ++gdr_test::Failures;                                                                   \
    }                                                                                         \
  } while (false)

// Records error and warning events of a filter.
struct EventLog
{
  std::vector<std::string> Errors;
  std::vector<std::string> Warnings;

  void Watch(vtkObject* object)
  {
    vtkNew<vtkCallbackCommand> cb;
    cb->SetClientData(this);
    cb->SetCallback(
      [](vtkObject*, unsigned long event, void* client, void* data)
      {
        auto* self = static_cast<EventLog*>(client);
        const std::string text = data ? static_cast<const char*>(data) : "";
        (event == vtkCommand::ErrorEvent ? self->Errors : self->Warnings).push_back(text);
      });
    object->AddObserver(vtkCommand::ErrorEvent, cb);
    object->AddObserver(vtkCommand::WarningEvent, cb);
  }
  static bool Contains(const std::vector<std::string>& list, const std::string& s)
  {
    return std::any_of(list.begin(), list.end(),
      [&](const std::string& e) { return e.find(s) != std::string::npos; });
  }
  bool ErrorContains(const std::string& s) const { return Contains(this->Errors, s); }
  bool WarningContains(const std::string& s) const { return Contains(this->Warnings, s); }
  void Clear()
  {
    this->Errors.clear();
    this->Warnings.clear();
  }
};

// main() of a test program: runs the test named by argv[1]; 0 when all its checks passed.
inline int RunNamedTest(
  int argc, char* argv[], const std::map<std::string, std::function<void()>>& tests)
{
  if (argc != 2 || !tests.count(argv[1]))
  {
    std::cerr << "usage: " << argv[0] << " <test>; tests:";
    for (const auto& t : tests)
    {
      std::cerr << " " << t.first;
    }
    std::cerr << std::endl;
    return 2;
  }
  tests.at(argv[1])();
  if (Failures)
  {
    std::cerr << argv[1] << ": " << Failures << " check(s) failed" << std::endl;
    return 1;
  }
  std::cout << argv[1] << ": passed" << std::endl;
  return 0;
}
} // namespace gdr_test
