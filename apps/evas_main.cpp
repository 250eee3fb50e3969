// evas: engine-vibration multibody simulation. Dispatches to the sub-commands
// in apps/cmd_*.cpp.
#include <malloc.h>

#include <boost/program_options/errors.hpp>
#include <cstring>
#include <iostream>

#include "apps/commands.h"
#include "apps/mpi_runner.h"
#include "integrators/plugin.h"
#include "model/types.h"

namespace {

const char* kUsage =
    "usage: evas <command> [options]\n"
    "\n"
    "commands:\n"
    "  run SCENE.yaml      simulate a scene; writes results.h5, summary.json (and results.csv)\n"
    "  periodic SCENE.yaml the steady cycle of a scene whose forcing repeats (engine cycle),\n"
    "                      with its iterations and Floquet multipliers\n"
    "  info BODY.h5        modes, mass properties and invariant checks of a modal-body file\n"
    "  export RESULTS.h5   convert a results file (--csv FILE)\n"
    "  body truss OUT.h5   generate a modal-body file of a truss beam\n"
    "  elements            reference of every force element and its parameters (Markdown)\n"
    "  modal build|import  FE pipeline (gmsh, ccx) and CalculiX import to a modal body\n"
    "  spectrum RESULTS.h5 order spectrum of a channel over whole engine cycles, or\n"
    "                      (--time) its amplitude, PSD and third-octave bands\n"
    "  plot KIND FILE.h5   figures of a run: channels, polar, orbit, film, order,\n"
    "                      order-track, spectrum, erp; of a study: waterfall, campbell,\n"
    "                      order-cuts (sweep.h5), work-precision (study.h5)\n"
    "  report RESULTS.h5   an engine run's page (--out DIR): bearings, loads, orders,\n"
    "                      torsion, surface velocity (DIR/index.html and figures)\n"
    "  study SUB SCENE     compare integrators: work-precision, convergence, stability;\n"
    "                      sweep (operating points, Campbell diagram), budget (error\n"
    "                      budget), compare (two study tables)\n"
    "  problem NAME        DAE test problems (andrews, car-axis, ...) scored in digits\n"
    "  bearing             the static answer of one journal bearing (film short, finite,\n"
    "                      reynolds): eccentricity, Sommerfeld number, K and C\n"
    "\n"
    "`evas <command> --help` describes the options of each command.\n"
    "`--plugin SPEC` (any command, repeatable) and EVAS_PLUGINS load integrator\n"
    "plug-ins (docs/extending.md).\n";

// Integrator plug-ins (integrators/plugin.h): every `--plugin SPEC` (or
// `--plugin=SPEC`) after the command is taken out of the arguments and loaded,
// as are those named in EVAS_PLUGINS, before the command sees its options.
void load_plugins(std::vector<std::string>& args) {
  evas::load_env_plugins();
  std::vector<std::string> rest;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (i > 0 && a == "--plugin") {
      if (i + 1 >= args.size())
        throw evas::InputError("--plugin needs a value: a path to a .so file or a plug-in name");
      evas::load_plugin(args[++i]);
    } else if (i > 0 && a.rfind("--plugin=", 0) == 0) {
      evas::load_plugin(a.substr(9));
    } else {
      rest.push_back(a);
    }
  }
  args = std::move(rest);
}

// The process keeps the memory it frees. By default glibc's malloc gives a
// large block (from 128 kB, its threshold rising as such blocks are freed) a
// mapping of its own that goes back to the system when freed, and trims the
// heap's top beyond 128 kB: a body file's megabytes of mode shapes, and their
// copies while the scene is built, are then faulted in page by page at every
// allocation, which on a virtual machine was a third of the start-up (docs/engine-speed.md,
// "Start-up"). Blocks below 256 MB now come from the heap, which grows 16 MB at a time and is
// trimmed only when 512 MB lie free at its top: a process's peak memory stays with it until it ends
// (one run, one study worker).
void keep_freed_memory() {
  mallopt(M_MMAP_THRESHOLD, 256 << 20);
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
  mallopt(M_TOP_PAD, 16 << 20);
}

}  // namespace

int main(int argc, char** argv) {
  keep_freed_memory();
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") ||
      !std::strcmp(argv[1], "help")) {
    (argc < 2 ? std::cerr : std::cout) << kUsage;
    return argc < 2 ? 1 : 0;
  }
  const std::string cmd = argv[1];
  if (cmd == "--version") {
    std::cout << "evas 0.1.0\n";
    return 0;
  }
  std::vector<std::string> args(argv + 1, argv + argc);
  // Under mpirun: ranks 1..N-1 serve rank 0's tasks (apps/mpi_runner.h);
  // rank 0 runs the command and lets them go when it ends.
  struct MpiEnd {
    ~MpiEnd() { evas::cli::mpi_finish(); }
  } mpi_end;
  try {
    // MPI first: the plug-ins then load after MPI_Init on every rank alike
    const auto job = evas::cli::mpi_start(&argc, &argv, cmd);
    load_plugins(args);
    if (job.active && job.rank > 0) return evas::cli::mpi_worker_loop();
    if (cmd == "run") return evas::cli::cmd_run(args);
    if (cmd == "periodic") return evas::cli::cmd_periodic(args);
    if (cmd == "info") return evas::cli::cmd_info(args);
    if (cmd == "export") return evas::cli::cmd_export(args);
    if (cmd == "body") return evas::cli::cmd_body(args);
    if (cmd == "elements") return evas::cli::cmd_elements(args);
    if (cmd == "modal") return evas::cli::cmd_modal(args);
    if (cmd == "spectrum") return evas::cli::cmd_spectrum(args);
    if (cmd == "plot") return evas::cli::cmd_plot(args);
    if (cmd == "report") return evas::cli::cmd_report(args);
    if (cmd == "study") return evas::cli::cmd_study(args);
    if (cmd == "problem") return evas::cli::cmd_problem(args);
    if (cmd == "bearing") return evas::cli::cmd_bearing(args);
  } catch (const boost::program_options::error& e) {
    std::cerr << "evas " << cmd << ": " << e.what() << " (see `evas " << cmd << " --help`)\n";
    return 1;
  } catch (const evas::InputError& e) {
    std::cerr << "evas " << cmd << ": " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "evas " << cmd << ": " << e.what() << "\n";
    return 2;
  }
  std::cerr << "evas: unknown command '" << cmd << "'\n\n" << kUsage;
  return 1;
}
