// TetGen's tetrahedralize in a child process, so that its failures cannot take the caller
// with them. Debian's library is built with assertions (tetgen.cxx 16432 in fillcavity
// fails on parts turned to an angle and on some scan-like surfaces, killing the process:
// gdr, or ParaView with the plugin), and the same facet recovery loops forever on some
// point orders of such surfaces. In a child, an assertion ends only the child, a loop is
// ended by a time limit, and the caller's abort hook works while TetGen runs.
#pragma once
#include <functional>
#include <string>

class tetgenio;

namespace gdr::cdt3d {

struct TetGenOutcome {
  enum Kind {
    Done,      // `out` holds TetGen's result
    Crashed,   // the child ended on `signal` (SIGABRT: an assertion) without a result
    TimedOut,  // no result within the time limit; the child was killed
  } kind = Done;
  int signal = 0;
};

// Runs tetrahedralize(switches, in) in a forked child and copies back into `out` the arrays
// the engines read: points and their markers, tetrahedra and neighbours, subfaces and their
// markers. An int thrown by TetGen (its error exits) becomes gdr::Error as TetGen describes
// it; `cancel` returning true kills the child and throws Error(Aborted). Where fork fails,
// TetGen runs in this process (an assertion then still ends the process).
TetGenOutcome run_tetgen_process(const std::string& switches, tetgenio& in, tetgenio& out,
                                 double seconds, const std::function<bool()>& cancel);

}  // namespace gdr::cdt3d
