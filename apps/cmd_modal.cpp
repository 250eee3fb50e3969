// evas modal build PARAMS.yaml | evas modal import ...: modal bodies from CalculiX.
#include <boost/program_options.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "apps/commands.h"
#include "bodies/body_builder.h"
#include "bodies/reduce_body.h"
#include "elements/plausibility.h"
#include "io/body_file.h"
#include "io/calculix.h"
#include "io/fe_pipeline.h"
#include "model/body_properties.h"

namespace evas::cli {

int cmd_modal(const std::vector<std::string>& args);

namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

void print_body(const std::string& out, const ModalBody& body) {
  const MassProperties mp = body_mass_properties(body);
  std::printf(
      "wrote %s: body '%s', %d nodes, %d modes, mass %.6g kg, centre of mass (%.6g, %.6g, "
      "%.6g) m\n",
      out.c_str(), body.name.c_str(), body.num_nodes(), body.num_modes(), mp.mass, mp.com.x(),
      mp.com.y(), mp.com.z());
  if (body.reduced())
    std::printf("reduced body: %d of %ld nodes kept (node sets and extra nodes), no mass matrix\n",
                body.num_nodes(), body.full_num_nodes);
  std::printf("elastic frequencies [Hz]:");
  for (int k = 0; k < body.num_modes(); ++k)
    if (body.kinds[k] == ModeKind::Elastic)
      std::printf(" %.6g", std::sqrt(std::max(0.0, body.eigenvalues[k])) / kTwoPi);
  std::printf("\n");
}

const char* kModalUsage =
    "usage: evas modal build PARAMS.yaml [--out DIR] [--quiet]\n"
    "       evas modal import --inp X.inp (--sti X.sti --mas X.mas --dof X.dof |\n"
    "                          --frd X.frd --dat X.dat --mas X.mas --dof X.dof) -o BODY.h5\n"
    "\n"
    "build:  runs gmsh -> ccx (matrix storage) -> the evas eigen-solver and writes the body\n"
    "        file named in PARAMS.yaml ('output', default NAME.h5) into DIR (default: the\n"
    "        current folder), its FE files into DIR/'work_dir' (default NAME-fe), and\n"
    "        prints the wall time of each stage. With\n"
    "        'reduce:' in PARAMS.yaml the body keeps only the nodes of its node sets (and\n"
    "        extra nodes) plus the stored invariants of the full body (docs/body-format.md).\n"
    "import: reads CalculiX output. With --sti the modes are computed by evas from K and M;\n"
    "        with --frd/--dat ccx's own modes are used (the mass matrix still comes from\n"
    "        --mas/--dof). See docs/fe-pipeline.md.\n";

int modal_build(const std::vector<std::string>& args) {
  po::options_description opts("options");
  opts.add_options()("help,h", "show this help")("quiet,q", "no stage timing")(
      "out,o", po::value<std::string>(),
      "folder of the body file and the FE work folder (default: the current folder)");
  po::options_description hidden;
  hidden.add_options()("params", po::value<std::string>(), "parameter file");
  po::options_description all;
  all.add(opts).add(hidden);
  po::positional_options_description pos;
  pos.add("params", 1);
  po::variables_map vm;
  po::store(po::command_line_parser(args).options(all).positional(pos).run(), vm);
  po::notify(vm);
  if (vm.count("help")) {
    std::cout << kModalUsage << "\n" << opts << "\n";
    return 0;
  }
  if (!vm.count("params")) {
    std::cerr << kModalUsage;
    return 1;
  }
  const bool verbose = !vm.count("quiet");
  const auto t0 = std::chrono::steady_clock::now();
  const PipelineParams p = read_pipeline_params(vm["params"].as<std::string>(),
                                                vm.count("out") ? vm["out"].as<std::string>() : "");
  if (verbose)
    std::printf("evas modal build: %s (work folder %s)\n", p.name.c_str(), p.work_dir.c_str());
  const PipelineResult r = run_pipeline(p, verbose);
  const auto t1 = std::chrono::steady_clock::now();
  write_body_file(p.output, r.body);
  if (verbose)
    std::printf("  %-28s %8.2f s\n  %-28s %8.2f s\n", "write body file",
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count(),
                "total",
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  print_body(p.output, r.body);
  if (!r.dat.empty()) {
    const DatModal d = read_dat_modal(r.dat);
    std::printf("ccx elastic frequencies [Hz]:  ");
    for (int k = 0; k < d.eigenvalues.size(); ++k)
      if (d.eigenvalues[k] > 1e-6 * d.eigenvalues.maxCoeff())
        std::printf(" %.6g", std::sqrt(d.eigenvalues[k]) / kTwoPi);
    std::printf("\n(ccx results: %s, %s)\n", r.frd.c_str(), r.dat.c_str());
  }
  return 0;
}

int modal_import(const std::vector<std::string>& args) {
  BuildOptions opt;
  opt.num_elastic = 10;
  po::options_description opts("options");
  opts.add_options()("help,h", "show this help")(
      "inp", po::value<std::string>(), "ccx deck (.inp)")("sti", po::value<std::string>(),
                                                          "stiffness (matrix storage .sti)")(
      "mas", po::value<std::string>(), "mass (matrix storage .mas)")(
      "dof", po::value<std::string>(), "equation map (matrix storage .dof)")(
      "frd", po::value<std::string>(), "ccx mode shapes (.frd)")(
      "dat", po::value<std::string>(), "ccx eigenvalues (.dat)")("out,o", po::value<std::string>(),
                                                                 "body file to write")(
      "name", po::value<std::string>()->default_value("body"), "body name")(
      "units", po::value<std::string>()->default_value("mm-t-s"),
      "unit system of the files: mm-t-s, SI, mm-kg-s")(
      "elastic", po::value<std::string>()->default_value(std::to_string(opt.num_elastic)),
      "elastic modes to keep: N >= 1 (the lowest N) or all")(
      "max-frequency", po::value<double>(&opt.max_frequency)->default_value(0.0),
      "keep elastic modes below this [Hz] (0 = no cut-off)")(
      "damping-ratio", po::value<double>(&opt.damping_ratio)->default_value(0.0),
      "modal damping ratio of the elastic modes")(
      "solver", po::value<std::string>(&opt.solver)->default_value("auto"),
      "eigen-solver for --sti: dense, spectra, auto")("no-rigid", "leave out the 6 rigid modes");
  po::variables_map vm;
  po::store(po::command_line_parser(args).options(opts).run(), vm);
  po::notify(vm);
  if (vm.count("help")) {
    std::cout << kModalUsage << "\n" << opts << "\n";
    return 0;
  }
  for (const char* k : {"inp", "mas", "dof", "out"})
    if (!vm.count(k)) throw InputError(std::string("evas modal import needs --") + k);
  const bool from_frd = vm.count("frd") > 0;
  if (from_frd == (vm.count("sti") > 0))
    throw InputError(
        "evas modal import needs either --sti (evas modes) or --frd and --dat "
        "(ccx modes)");
  if (from_frd && !vm.count("dat")) throw InputError("evas modal import: --frd needs --dat");
  opt.num_elastic = parse_elastic_option(vm["elastic"].as<std::string>());
  if (opt.damping_ratio < 0.0 || opt.max_frequency < 0.0)
    throw InputError("--max-frequency and --damping-ratio must be >= 0");
  opt.keep_rigid = !vm.count("no-rigid");
  const UnitSystem units = unit_system(vm["units"].as<std::string>());
  const auto str = [&](const char* k) { return vm[k].as<std::string>(); };
  const InpMesh mesh = read_inp(str("inp"));
  const FeModel fe =
      read_matrix_storage(mesh, from_frd ? "" : str("sti"), str("mas"), str("dof"), units);
  const std::string name = str("name");
  const ModalBody body = from_frd ? body_from_ccx_modes(name, fe, read_frd_modes(str("frd")),
                                                        read_dat_modal(str("dat")), opt)
                                  : build_modal_body(name, fe, opt);
  write_body_file(str("out"), body);
  print_body(str("out"), body);
  // a mesh in millimetres read as SI (or the reverse): said, not silently kept
  const MassProperties mp = body_mass_properties(body);
  const Vec3 extent = (body.s.colwise().maxCoeff() - body.s.colwise().minCoeff()).transpose();
  const std::vector<MeshUnits> systems = {
      {"SI", 1.0, 1.0}, {"mm-t-s", 1e-3, 1e3}, {"mm-kg-s", 1e-3, 1.0}};
  const std::string w = mesh_units_warning(
      mp.mass, extent, {vm["units"].as<std::string>(), units.length, units.mass}, systems);
  if (!w.empty()) std::cerr << "evas modal import: warning: " << w << "\n";
  return 0;
}

}  // namespace

int cmd_modal(const std::vector<std::string>& args) {
  if (args.size() < 2 || args[1] == "--help" || args[1] == "-h") {
    std::cout << kModalUsage;
    return args.size() < 2 ? 1 : 0;
  }
  const std::vector<std::string> rest(args.begin() + 2, args.end());
  if (args[1] == "build") return modal_build(rest);
  if (args[1] == "import") return modal_import(rest);
  std::cerr << "evas modal: unknown action '" << args[1] << "' (build, import)\n" << kModalUsage;
  return 1;
}

}  // namespace evas::cli
