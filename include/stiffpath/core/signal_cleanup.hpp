// Removal of temporary output files when the process is interrupted (SIGINT, SIGTERM, SIGHUP).
#pragma once

namespace stiffpath::core {

//! Records a temporary path to remove if a cleanup signal arrives; returns its slot, or -1 when the
//! fixed table (64 paths of up to 4 KiB) is full or the path too long (the file is then not covered).
int register_temporary(const char* path) noexcept;

//! Forgets a slot from register_temporary() (after the file was renamed or removed). -1 is ignored.
void unregister_temporary(int slot) noexcept;

//! Installs handlers for SIGINT, SIGTERM and SIGHUP that unlink(2) every registered temporary file
//! and _exit(128 + signal). Async-signal-safe: the handler reads a fixed table and calls only unlink
//! and _exit. Call once at program start (the CLI does); libraries embedding stiffpath may skip it.
void install_signal_cleanup();

}  // namespace stiffpath::core
