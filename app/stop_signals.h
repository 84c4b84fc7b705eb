#pragma once
// SIGINT and SIGTERM: before exiting with the conventional status (130,
// 143), sdgbehave says where the run was: the prim, behavior, hook and
// frame, and the script's file:line when a script was running.
namespace sdg::cli {

// Installs the handlers and starts the thread that reports and exits.
// Commands that handle the signals themselves (studio) do not call it.
void installStopSignalHandlers();

}  // namespace sdg::cli
