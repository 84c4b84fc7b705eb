#pragma once
// Loading behavior scripts into a registry: the script runs once per process
// (its top-level code, as an import does), every Behavior subclass with its
// own BEHAVIOR_NS becomes a behavior whose spec comes from its
// VARIABLES_TO_EXPOSE, registered beside the built-ins and plugins.
#include <string>
#include <vector>

#include "behavior/registry.h"
#include "core/source_loc.h"

namespace sdg::scripting {

// Loads `path` (as given, relative to the working folder) and registers its
// behaviors. A missing file is located at `where`; a syntax error, an
// exception in the top-level code, a bad BEHAVIOR_NS or VARIABLES_TO_EXPOSE
// entry, or a namespace another source already uses is a SceneError at the
// script's file:line. Loading the same file into the same registry again
// does nothing. Returns the behaviors (namespaces) the file defines.
std::vector<std::string> loadScript(BehaviorRegistry& registry, const std::string& path, const SourceLoc& where);

// A SceneError at `where` unless `path` is an existing regular file ending
// in .py: a missing file, a folder and (say) a scene each say so, instead of
// a SyntaxError from reading YAML as Python.
void checkScriptFile(const std::string& path, const SourceLoc& where);

// Runs `path` again (after it changed on disk), so that registries loaded
// from now on get its new classes. When it no longer loads, the SceneError
// says why (file:line) and the last good version stays in use.
void reloadScript(const std::string& path);

}  // namespace sdg::scripting
