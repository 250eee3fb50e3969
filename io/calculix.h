// Import of CalculiX (ccx 2.20) models and results (docs/fe-pipeline.md).
//
//   read_inp            nodes, elements and named sets of an Abaqus/ccx .inp deck
//   read_matrix_storage K and the scalar consistent mass Ms from the job.sti,
//                       job.mas and job.dof files of *FREQUENCY, SOLVER=MATRIXSTORAGE
//   read_frd_modes      mode shapes (DISP blocks) of a .frd result file
//   read_dat_modal      eigenvalues, participation factors and effective masses
//                       printed in the .dat file by *FREQUENCY
//   body_from_ccx_modes a ModalBody from ccx's own eigenmodes
//
// Everything is keyed by node id, never by position. Values in the files are in
// the deck's unit system (usually mm-t-s-N); a UnitSystem converts them to SI.
// Errors are InputError messages naming the file, the line and what is wrong.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "bodies/body_builder.h"
#include "bodies/truss.h"
#include "model/modal_body.h"

namespace evas {

/// Size of the deck's length and mass units in SI (time is in seconds).
/// Force unit = mass * length / s^2, so K [force/length] scales by `mass`.
struct UnitSystem {
  double length = 1.0;  ///< [m] per file length unit
  double mass = 1.0;    ///< [kg] per file mass unit
};

/// "SI" / "m-kg-s" (1, 1), "mm-t-s" (1e-3, 1e3), "mm-kg-ms" is not supported
/// (time must be s). Throws InputError for unknown names.
UnitSystem unit_system(const std::string& name);

/// One *ELEMENT block.
struct InpElementBlock {
  std::string type;                      ///< e.g. C3D10 (upper case)
  std::string elset;                     ///< ELSET= of the block ("" if none)
  std::vector<long> ids;                 ///< element ids
  std::vector<std::vector<long>> nodes;  ///< node ids of each element
};

/// Contents of an .inp deck (values in the deck's units).
struct InpMesh {
  std::vector<long> node_ids;                  ///< in order of appearance (unique)
  Eigen::Matrix<double, Eigen::Dynamic, 3> s;  ///< N x 3 coordinates
  std::vector<InpElementBlock> elements;
  /// *NSET sets (and *NODE, NSET=) plus node sets derived from *ELSET sets that
  /// have no *NSET of the same name. Names as written in the deck.
  std::map<std::string, std::vector<long>> node_sets;
  std::map<std::string, std::vector<long>> element_sets;  ///< *ELSET and *ELEMENT, ELSET=

  /// Row of a node id, or -1.
  int index_of(long id) const;
  std::map<long, int> index;  ///< node id -> row
};

/// Reads an .inp deck, following *INCLUDE (relative to the including file).
/// Handles *NODE (with NSET=), *ELEMENT (continuation lines), *NSET and *ELSET
/// (with GENERATE and references to other sets); other keywords are skipped.
InpMesh read_inp(const std::string& path);

/// Element types that carry mass and stiffness in 3-D (C3D*).
bool is_solid_element(const std::string& type);

/// Per-node areas [m^2] and outward unit normals of every element set of the
/// mesh made of 2-D (face) elements only, keyed by set name
/// (io/calculix_surface.cpp: tributary shares of each face's area, outward
/// from the solid element behind it). `path` names the deck in errors: a face
/// with no solid behind it or between two solids, a degenerate face.
std::map<std::string, SurfaceSet> mesh_surfaces(const InpMesh& mesh, const UnitSystem& units,
                                                const std::string& path);

/// FeModel from ccx matrix storage. `sti` may be empty (K is then left empty,
/// e.g. when only the mass is wanted). Nodes are those of `mesh` that carry
/// DOF in the .dof file, in the mesh's order; every such node must carry all
/// three translations. M = Ms (x) I3 is checked: an entry coupling different
/// directions or differing between directions is an error. Node sets keep the
/// nodes that are in the model.
FeModel read_matrix_storage(const InpMesh& mesh, const std::string& sti, const std::string& mas,
                            const std::string& dof, const UnitSystem& units);

/// Mode shapes of a .frd file (DISP blocks, file units).
struct FrdModes {
  std::vector<long> node_ids;       ///< nodes of the first DISP block, in file order
  Mat shapes;                       ///< 3N x n, row 3i+a (i in node_ids order)
  std::vector<double> frequencies;  ///< value of each block's 100CL record [cycles/time]
  std::vector<int> mode_numbers;    ///< mode number of each block
};
FrdModes read_frd_modes(const std::string& path);

/// Parses one fixed-width .frd node record " -1" + I10 node + n x E12.5 values.
/// Returns false if the line is not a node record. Exposed for tests.
bool parse_frd_node_line(const std::string& line, long& node, std::vector<double>& values);

/// Modal tables of a .dat file (first *FREQUENCY step found).
struct DatModal {
  Vec eigenvalues;                    ///< lambda [rad^2/time^2], file units
  Mat participation;                  ///< n x 6 (x, y, z, rot x, rot y, rot z), may be empty
  Mat effective_mass;                 ///< n x 6, may be empty
  Eigen::Matrix<double, 6, 1> total;  ///< total effective mass (mass units; rotations
                                      ///< in mass * length^2 about the global axes)
  bool has_total = false;
};
DatModal read_dat_modal(const std::string& path);

/// ModalBody from ccx eigenmodes. `fe` supplies node ids, coordinates (SI), Ms (SI)
/// and sets (K is not used); `modes` the shapes, `dat` the eigenvalues. The modes
/// whose eigenvalue is below 1e-6 of the largest (at most 6) are the rigid modes
/// and are replaced by rigid_basis(); the elastic shapes are projected against it
/// and mass-normalised again (the .frd holds ~6 digits), then truncated as in
/// build_modal_body (count / cut-off) with `opt`.
ModalBody body_from_ccx_modes(const std::string& name, const FeModel& fe, const FrdModes& modes,
                              const DatModal& dat, const BuildOptions& opt);

/// Writes the nodes, the solid elements (in one set EALL) and the node sets of
/// `mesh` as a ccx deck fragment: surface elements written by Gmsh (CPS6 ...)
/// are dropped. Node sets keep only nodes used by solid elements.
void write_ccx_mesh(const std::string& path, const InpMesh& mesh);

}  // namespace evas
