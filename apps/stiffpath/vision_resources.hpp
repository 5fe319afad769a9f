// Running out of memory or threads in the image commands: a refusal that names the limit (exit 2), not an internal error.
#pragma once

#include <functional>
#include <string>

namespace stiffpath::cli {

//! Runs `work`, turning a failure to get memory or a thread — std::bad_alloc, a std::system_error of a thread that
//! cannot start, OpenCV's "Insufficient memory" or "pthread_create has failed" — into stiffpath::Error at `file`:
//! what `task` needed (`needs_bytes`, when known) against the process's memory limit (ulimit -v) or the memory
//! the machine has free. Other exceptions pass through unchanged.
void within_resources(const std::string& file, const std::string& task, double needs_bytes, const std::function<void()>& work);

}  // namespace stiffpath::cli
