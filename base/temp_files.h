// Temporary files that must not outlive the process: OutputFile registers the hidden temporary it
// writes next to its destination, and a signal that ends the process (SIGINT, SIGTERM, SIGHUP,
// SIGQUIT, SIGPIPE, SIGXFSZ, SIGABRT) removes every registered file before the process dies of that
// signal as it would have without us. The handler is async-signal-safe: it only reads fixed slots
// and calls unlink(2), sigaction(2) and raise(3). It is installed when a file is registered, for
// the signals whose disposition is still the default (a signal the caller ignores or handles is
// left alone). SIGKILL and power loss cannot be caught: a `.NAME.tmp-XXXXXX` file may remain then.
#pragma once

namespace tranche::temp_files {

// Registers `path` (copied into a fixed slot); returns the slot, or -1 when every slot is taken
// or the path is too long (the file is then only removed by its owner, as before).
int add(const char* path);
// Forgets a slot (after the file was renamed into place or removed). -1 is ignored.
void remove(int slot);
// Unlinks every registered file now (async-signal-safe): for exits that skip destructors.
void unlink_all() noexcept;

}  // namespace tranche::temp_files
