// A read that libhdf5 may not survive, run in a child process (used by io/;
// set_read_isolation for the fuzz harness).
//
// libhdf5 (1.10.8, Debian 12) reads a variable-length string through the
// file's global heap and trusts the heap's object sizes and addresses: one
// corrupt size makes it copy gigabytes (a crash), a corrupt collection can make
// it loop for ever (docs/fuzzing.md). evas cannot mend the library, so such a
// read runs in a forked child that sends the strings back through a pipe: a
// child that dies or hangs becomes a Failure naming what was read, and the
// caller's process goes on.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace evas::h5 {

/// Runs read() in a child process and returns its strings. Throws Failure
/// ("<what> cannot be read: ...") when read() throws, when the child ends by a
/// signal (libhdf5 crashed on the file) or runs longer than timeout_s. When no
/// child can be started (fork fails), read() runs in this process, and so does a
/// read_isolated() called within read(): several reads share one child.
std::vector<std::string> read_isolated(const std::function<std::vector<std::string>()>& read,
                                       const std::string& what, double timeout_s = 20.0);

/// On by default. Off, read_isolated() runs read() in this process: the
/// body-file fuzz harness turns it off so that libFuzzer sees libhdf5's faults
/// itself and classifies them (in a child they are out of its sight, and its
/// hooks there would save the input as a finding while this process goes on).
void set_read_isolation(bool on);

}  // namespace evas::h5
