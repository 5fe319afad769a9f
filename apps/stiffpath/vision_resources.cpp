// Running out of memory or threads in the image commands (scan, render-scan): a located refusal naming the limit.
#include "vision_resources.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <cstring>
#include <fmt/format.h>
#include <new>
#include <opencv2/core.hpp>
#include <system_error>

#include "stiffpath/core/error.hpp"

namespace stiffpath::cli {

namespace {

// "this process may use at most N MiB of address space (ulimit -v)", or the machine's free memory.
std::string limit_text() {
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    return fmt::format("this process may use at most {:.0f} MiB of address space (ulimit -v), OpenCV's own libraries and threads included",
                       static_cast<double>(limit.rlim_cur) / 1048576.0);
  }
  const long pages = sysconf(_SC_AVPHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  if (pages > 0 && page > 0) return fmt::format("the machine has {:.0f} MiB free", static_cast<double>(pages) * static_cast<double>(page) / 1048576.0);
  return "the memory available ran out";
}

[[noreturn]] void refuse(const std::string& file, const std::string& task, double needs_bytes, const std::string& what) {
  throw Error(SourceLocation{file, 0, 0},
              fmt::format("RESOURCE: out of memory while {} ({}){}; {}: free memory, raise the limit, or use a smaller image", task, what,
                          needs_bytes > 0 ? fmt::format(": it needs about {:.0f} MiB", needs_bytes / 1048576.0) : std::string(),
                          limit_text()));
}

bool names_exhaustion(const std::string& what) {
  for (const char* sign : {"pthread_create", "Insufficient memory", "Failed to allocate", "bad_alloc", "out of memory"}) {
    if (what.find(sign) != std::string::npos) return true;
  }
  return false;
}

}  // namespace

void within_resources(const std::string& file, const std::string& task, double needs_bytes, const std::function<void()>& work) {
  try {
    work();
  } catch (const std::bad_alloc& e) {
    refuse(file, task, needs_bytes, "a memory allocation failed");
  } catch (const std::system_error& e) {
    if (e.code() != std::errc::resource_unavailable_try_again && e.code() != std::errc::not_enough_memory) throw;
    refuse(file, task, needs_bytes, std::string("a thread could not start: ") + e.what());
  } catch (const cv::Exception& e) {
    if (e.code != cv::Error::StsNoMem && !names_exhaustion(e.what())) throw;
    refuse(file, task, needs_bytes, e.err.empty() ? std::string(e.what()) : e.err);
  } catch (const stiffpath::Error&) {
    throw;
  } catch (const std::exception& e) {
    if (!names_exhaustion(e.what())) throw;
    refuse(file, task, needs_bytes, e.what());
  }
}

}  // namespace stiffpath::cli
