#include "scripting/script_imports.h"

#include <algorithm>
#include <filesystem>
#include <set>

#include "scripting/python_host.h"

namespace sdg::scripting {
namespace fs = std::filesystem;
namespace py = pybind11;

namespace {

bool isBelow(const std::string& file, const std::string& folder) {
  const std::string prefix = folder.ends_with('/') ? folder : folder + "/";
  return file.starts_with(prefix);
}

}  // namespace

std::vector<std::string> importedSourceFiles(const std::vector<std::string>& scriptFiles) {
  if (scriptFiles.empty() || !PythonHost::started()) return {};
  std::set<std::string> scripts, folders;
  for (const std::string& s : scriptFiles) {
    const fs::path p = fs::absolute(s).lexically_normal();
    scripts.insert(p.string());
    folders.insert(p.parent_path().string());
  }
  std::set<std::string> found;
  PythonHost::instance();
  py::gil_scoped_acquire gil;
  py::dict modules = py::module_::import("sys").attr("modules");
  for (auto item : modules) {
    py::object file = py::getattr(item.second, "__file__", py::none());
    if (!py::isinstance<py::str>(file)) continue;
    std::string path = fs::absolute(file.cast<std::string>()).lexically_normal().string();
    if (!path.ends_with(".py") || scripts.count(path)) continue;
    for (const std::string& folder : folders)
      if (isBelow(path, folder)) {
        found.insert(path);
        break;
      }
  }
  return {found.begin(), found.end()};
}

}  // namespace sdg::scripting
