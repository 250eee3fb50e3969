// Reduced modal bodies: keep only the nodes that markers and outputs need.
//
// A simulation touches the nodes of a modal body in two ways only: through the
// modal invariants and mass properties (sums over all nodes, computed once
// when the body is added to a model) and through markers and outputs (rows of
// the mode shapes at a few nodes). Once the invariants and mass properties of
// the full body are stored with it, every other node can be dropped: a body of
// 100k nodes shrinks to the few thousand of its bearing and mount surfaces,
// and a Model built from it gives the same equations to round-off.
//
// What a reduced body cannot give is anything that sums over the full node set
// again: the full mass matrix, rigid_basis() over all nodes, interface modes,
// eq1_literal(). Those are refused with an InputError naming the body file
// (ModalBody::require_full); the rigid-body participation of the modes and the
// location of the rigid basis modes come from the stored invariants instead.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "model/body_properties.h"

namespace evas {

struct ReduceOptions {
  bool all_sets = true;                ///< keep the nodes of every named node set
  std::vector<std::string> keep_sets;  ///< else: only these sets (the others are dropped)
  std::vector<long> extra_nodes;       ///< further node ids kept (e.g. for outputs)
};

/// Computes and attaches the invariants and mass properties of a full body
/// (from all its nodes and its mass matrix). Throws for a reduced body.
void store_full_body_data(ModalBody& body);

/// The body restricted to the nodes of the kept sets and the extra nodes (in
/// the original node order), with their mode-shape rows, the kept sets, the
/// stored invariants and mass properties of the full body (computed here if
/// the body does not carry them yet) and no mass matrix. Unknown set names or
/// node ids are an InputError naming the body. A reduced body may be reduced
/// further.
ModalBody reduce_body(const ModalBody& body, const ReduceOptions& opt);

}  // namespace evas
