// evas body truss OUT.h5: generate a modal-body file of a truss beam.
#include <algorithm>
#include <boost/program_options.hpp>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "apps/commands.h"
#include "bodies/body_builder.h"
#include "bodies/truss.h"
#include "io/body_file.h"

namespace evas::cli {

int cmd_body(const std::vector<std::string>& args) {
  TrussBeamSpec spec;
  BuildOptions opt;
  opt.num_elastic = 10;
  std::vector<double> origin = {0.0, 0.0, 0.0};
  po::options_description opts(
      "usage: evas body truss OUT.h5 [options]\n\n"
      "Builds a space-truss beam (point masses and axial bars, square section, bays along x),\n"
      "computes its modes and writes a modal-body file. Node sets: end0, end1, section<k>,\n"
      "all.\n\n"
      "options");
  opts.add_options()("help,h", "show this help")(
      "name", po::value<std::string>()->default_value("truss"), "body name")(
      "segments", po::value<int>(&spec.segments)->default_value(spec.segments), "bays along x")(
      "length", po::value<double>(&spec.length)->default_value(spec.length), "length [m]")(
      "width", po::value<double>(&spec.width)->default_value(spec.width), "section side [m]")(
      "youngs", po::value<double>(&spec.youngs)->default_value(spec.youngs), "bar modulus [Pa]")(
      "area", po::value<double>(&spec.area)->default_value(spec.area), "bar section [m^2]")(
      "density", po::value<double>(&spec.density)->default_value(spec.density),
      "bar density [kg/m^3]")("origin", po::value<std::vector<double>>()->multitoken(),
                              "centre of the first section: X Y Z [m]")(
      "elastic", po::value<std::string>()->default_value(std::to_string(opt.num_elastic)),
      "elastic modes to keep: N >= 1 (the lowest N) or all")(
      "max-frequency", po::value<double>(&opt.max_frequency)->default_value(0.0),
      "keep elastic modes below this [Hz] (0 = no cut-off)")(
      "damping-ratio", po::value<double>(&opt.damping_ratio)->default_value(0.0),
      "modal damping ratio of the elastic modes")("no-rigid", "leave out the 6 rigid modes");
  po::variables_map vm;
  if (parse_args(args, opts, {"kind", "out"}, vm)) return 0;
  if (!vm.count("kind") || !vm.count("out")) {
    std::cerr << "evas body: need a kind (truss) and an output file\n" << opts << "\n";
    return 1;
  }
  if (vm["kind"].as<std::string>() != "truss")
    throw InputError("unknown body kind '" + vm["kind"].as<std::string>() + "' (known: truss)");
  if (vm.count("origin")) {
    origin = vm["origin"].as<std::vector<double>>();
    if (origin.size() != 3) throw InputError("--origin needs 3 values");
  }
  opt.num_elastic = parse_elastic_option(vm["elastic"].as<std::string>());
  const long nodes = 4L * (std::max(spec.segments, 1) + 1), dof = 3 * nodes;
  if ((spec.segments >= 1 && opt.num_elastic > dof - 6) || opt.num_elastic > kMaxGeneratedModes)
    throw InputError("--elastic " + std::to_string(opt.num_elastic) + ": the truss has " +
                     std::to_string(dof - 6) + " elastic modes, and at most " +
                     std::to_string(kMaxGeneratedModes) + " are kept");
  if (spec.segments >= 1 && opt.num_elastic == 0 && dof > kMaxDenseDof)
    throw InputError("--elastic all needs the dense eigen-solver, limited to " +
                     std::to_string(kMaxDenseDof) + " DOF; the truss has " + std::to_string(dof) +
                     ": give --elastic K");
  if (opt.damping_ratio < 0.0) throw InputError("--damping-ratio must be >= 0");
  spec.origin = Vec3(origin[0], origin[1], origin[2]);
  opt.keep_rigid = !vm.count("no-rigid");
  const std::string name = vm["name"].as<std::string>();
  const std::string out = vm["out"].as<std::string>();
  const ModalBody body = build_modal_body(name, make_truss_beam(spec), opt);
  write_body_file(out, body);
  std::printf("wrote %s: body '%s', %d nodes, %d modes; elastic frequencies [Hz]:", out.c_str(),
              name.c_str(), body.num_nodes(), body.num_modes());
  for (int k = 0; k < body.num_modes(); ++k)
    if (body.kinds[k] == ModeKind::Elastic)
      std::printf(" %.5g", std::sqrt(std::max(0.0, body.eigenvalues[k])) / (2.0 * M_PI));
  std::printf("\n");
  return 0;
}

}  // namespace evas::cli
