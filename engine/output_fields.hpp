// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The optional fields a run can write to its results (scene key `[output] fields`), computed
// from the model as it is between two steps. Each call fills its output (resized), allocates
// nothing else after the first call, and gives the same bits on every thread count (serial,
// in element or node order).
//   log_strain        per element, 6 (xx yy zz xy yz xz): the Hencky strain 0.5 ln(F F^T),
//                     averaged over the 4 Gauss points as the stress is
//   nodal_stress      per node, 6: the Cauchy stress of the elements around the node, averaged
//                     with their reference volumes as weights (a smooth field for contour plots)
//   contact_force     per node, 3: the contact force on the node (walls, other bodies, and the
//                     impact dashpot's share, which acts on every node of a body)
//   contact_pressure  per node, 1: the normal contact pressure on the current surface (positive
//                     in compression): each boundary face's normal contact force over its area
//                     (see the .cpp for how a node's force is shared among its faces), averaged
//                     over the faces around the node with their areas; 0 inside and on a free
//                     surface
//   body_velocity     per node, 3: the velocity of the centre of mass of the node's body
//   node_body         per node: the node's body index, which results.h5 has in /mesh/node_body;
//                     nothing to compute (the results writer names it in results.xdmf)
#include <string>
#include <vector>

#include "elements/tet10_surface.hpp"
#include "engine/model.hpp"

namespace femdem {

// The names `[output] fields` accepts, in the order results.h5 lists them.
inline const std::vector<std::string> kOptionalOutputFields = {
    "log_strain", "nodal_stress", "contact_force", "contact_pressure", "body_velocity",
    "node_body"};

class OutputFields {
 public:
  explicit OutputFields(const Model& m);

  void log_strain(const Model& m, std::vector<double>& strain6) const;
  // `element_stress6`: 6 per element (Simulation::element_stress).
  void nodal_stress(const Model& m, const std::vector<double>& element_stress6,
                    std::vector<double>& nodal6) const;
  void contact_pressure(const Model& m, std::vector<double>& pressure) const;
  void body_velocity(const Model& m, std::vector<double>& velocity3) const;

 private:
  std::vector<BoundaryFace> faces_;
  std::vector<double> node_volume_;  // sum of the reference volumes of its elements
  std::vector<std::size_t> node_face_start_, node_faces_;         // boundary faces around each node
  std::vector<double> node_face_share_;                           // the node's share of each
  mutable std::vector<double> face_normal_, face_area_, weight_;  // scratch
};

}  // namespace femdem
