#include "insitu/catalyst/virtual_display.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace dustlift {

VirtualDisplay::VirtualDisplay() {
  int fds[2];
  if (pipe(fds) != 0) throw std::runtime_error("Xvfb: cannot create a pipe");
  pid_ = fork();
  if (pid_ < 0) throw std::runtime_error("Xvfb: cannot fork");
  if (pid_ == 0) {
    // Own process group: a Ctrl-C at the terminal stops dustlift (which checkpoints), not its
    // display first; and the server ends with dustlift even if dustlift is killed.
    setpgid(0, 0);
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    close(fds[0]);
    const int null = open("/dev/null", O_WRONLY);
    if (null >= 0) {
      dup2(null, STDOUT_FILENO);
      dup2(null, STDERR_FILENO);
    }
    const std::string fd = std::to_string(fds[1]);
    // -noreset: a server resets when its last client leaves, and a connection made during the
    // reset fails (scripts/with-xvfb.sh says more).
    execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "1920x1200x24", "-nolisten",
           "tcp", "-noreset", static_cast<char*>(nullptr));
    _exit(127);
  }
  close(fds[1]);
  std::string number;
  pollfd p{fds[0], POLLIN, 0};
  for (;;) {
    const int ready = poll(&p, 1, 30'000);
    if (ready <= 0) break;  // timeout (or error): no display within 30 s
    char c;
    const ssize_t got = read(fds[0], &c, 1);
    if (got <= 0 || c == '\n') break;
    number += c;
  }
  close(fds[0]);
  if (number.empty()) {
    kill(pid_, SIGTERM);
    int status = 0;
    waitpid(pid_, &status, 0);
    pid_ = -1;
    throw std::runtime_error(
        "no X display (DISPLAY is unset) and Xvfb could not start: install xvfb "
        "(scripts/install-deps.sh) or run "
        "under a display");
  }
  display_ = ":" + number;
  setenv("DISPLAY", display_.c_str(), 1);
}

VirtualDisplay::~VirtualDisplay() {
  if (pid_ > 0) {
    kill(pid_, SIGTERM);
    int status = 0;
    while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    unsetenv("DISPLAY");
  }
}

}  // namespace dustlift
