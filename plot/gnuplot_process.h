// A gnuplot process started before its figures exist. Starting gnuplot and its
// cairo terminal (the program, its libraries, the fonts) takes 0.06 to 0.1 s
// here, more than drawing a small figure; a command that knows early that it
// will draw (a sweep, while it reads its scene and runs its points) starts the
// process then, and the start overlaps that work instead of following it.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <vector>

namespace evas {

class GnuplotProcess {
 public:
  /// Starts gnuplot (when it is on the PATH) reading commands from a socket,
  /// and has it draw one throw-away figure to /dev/null so that the terminal
  /// and fonts are loaded now.
  GnuplotProcess();
  /// Ends a process that has not drawn: closes its input and waits for it.
  ~GnuplotProcess();
  GnuplotProcess(const GnuplotProcess&) = delete;
  GnuplotProcess& operator=(const GnuplotProcess&) = delete;

  /// True while a started process is waiting for its figures.
  bool ready() const { return pid_ > 0; }
  /// Runs the scripts (all in one folder, each naming its output without a
  /// folder) in that folder, in order, then ends the process and waits for
  /// it. False when the process was not ready or gnuplot did not end well
  /// (the caller checks which figures exist). Once only.
  bool draw(const std::vector<std::filesystem::path>& scripts);

 private:
  pid_t pid_ = -1;
  int fd_ = -1;  ///< our end of the socket: gnuplot's standard input
  bool send(const std::string& text);
  int finish();  ///< closes the input, waits; the exit status (-1 abnormal)
};

}  // namespace evas
