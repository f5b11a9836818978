// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Named parameters of the package, in CGAL's style. CGAL 5.5's list of tags is closed,
// so the package's own tags live here, in a parameter class that derives from CGAL's:
// our options chain with each other and with CGAL's built-in ones, e.g.
//
//   namespace PIP = CGAL::Polycube_IGA::parameters;
//   PIP::merge_duplicate_vertices(true).remove_isolated_vertices(true).vertex_point_map(vpm)
//
// Our options must come before CGAL's in a chain (CGAL's members return CGAL's class).

#ifndef CGAL_POLYCUBE_IGA_PARAMETERS_H
#define CGAL_POLYCUBE_IGA_PARAMETERS_H

#include <CGAL/Named_function_parameters.h>

namespace CGAL {
namespace Polycube_IGA {

// The package's options: (tag, function name). One line per option.
#define CGAL_POLYCUBE_IGA_NAMED_PARAMETERS(X)                                        \
  /* reading and validation */                                                      \
  X(merge_duplicate_vertices_t, merge_duplicate_vertices)                           \
  X(remove_isolated_vertices_t, remove_isolated_vertices)                           \
  X(check_self_intersections_t, check_self_intersections)                           \
  X(maximum_examples_t, maximum_examples)                                           \
  /* topology */                                                                    \
  X(loop_edge_weight_t, loop_edge_weight)                                           \
  X(number_of_roots_t, number_of_roots)                                             \
  X(compute_tunnel_loops_t, compute_tunnel_loops)                                   \
  X(maximum_refinements_t, maximum_refinements)                                     \
  X(small_handle_length_t, small_handle_length)                                     \
  /* pants decomposition */                                                         \
  X(cut_criterion_t, cut_criterion)                                                 \
  X(symmetry_plane_t, symmetry_plane)                                               \
  X(criterion_strength_t, criterion_strength)                                       \
  X(cut_pair_trials_t, cut_pair_trials)                                             \
  X(cuts_away_from_holes_t, cuts_away_from_holes)                                   \
  X(surface_topology_t, surface_topology)                                           \
  /* cuboid decomposition */                                                        \
  X(belt_phase_t, belt_phase)                                                       \
  X(corners_off_steps_t, corners_off_steps)                                         \
  X(balance_pants_corners_t, balance_pants_corners)                                 \
  X(sphere_chain_t, sphere_chain)                                                   \
  X(orthogonal_blocks_t, orthogonal_blocks)                                         \
  X(polycube_map_t, polycube_map)                                                   \
  /* spline fitting (lambda_1..3 of eq. 4.1) */                                     \
  X(stretching_weight_t, stretching_weight)                                         \
  X(bending_weight_t, bending_weight)                                               \
  X(data_weight_t, data_weight)                                                     \
  X(spline_degree_t, spline_degree)                                                 \
  X(number_of_spans_t, number_of_spans)                                             \
  /* patch sampling */                                                              \
  X(grid_resolution_t, grid_resolution)                                             \
  X(smooth_interior_patches_t, smooth_interior_patches)                             \
  X(stretch_rounds_t, stretch_rounds)                                               \
  X(fold_bending_weight_t, fold_bending_weight)                                     \
  X(sharp_boundary_turn_t, sharp_boundary_turn)                                     \
  /* volume */                                                                      \
  X(boundary_layer_t, boundary_layer)                                               \
  X(maximum_cuboid_aspect_t, maximum_cuboid_aspect)                                 \
  X(untangle_volume_t, untangle_volume)                                             \
  X(untangle_invalid_result_t, untangle_invalid_result)                             \
  X(focused_sample_rounds_t, focused_sample_rounds)                                 \
  X(grid_relaxation_sweeps_t, grid_relaxation_sweeps)                               \
  X(maximum_boundary_distance_t, maximum_boundary_distance)                         \
  X(maximum_grid_resolution_t, maximum_grid_resolution)                             \
  X(minimum_grid_resolution_t, minimum_grid_resolution)                             \
  X(minimum_spline_degree_t, minimum_spline_degree)                                 \
  X(belt_phases_t, belt_phases)                                                     \
  X(step_retry_t, step_retry)                                                       \
  X(arc_relaxation_sweeps_t, arc_relaxation_sweeps)                               \
  X(node_relocation_sweeps_t, node_relocation_sweeps)                             \
  X(node_relocation_retry_t, node_relocation_retry)                               \
  X(missing_part_cubes_t, missing_part_cubes)                                     \
  X(polycube_retry_t, polycube_retry)                                             \
  X(cuts_away_retry_t, cuts_away_retry)                                           \
  X(polycube_first_alignment_t, polycube_first_alignment)                         \
  X(polycube_arc_relaxation_sweeps_t, polycube_arc_relaxation_sweeps)             \
  X(untangling_budget_t, untangling_budget)

namespace internal_np {
#define CGAL_POLYCUBE_IGA_DECLARE_TAG(TAG, NAME) enum TAG { NAME };
CGAL_POLYCUBE_IGA_NAMED_PARAMETERS(CGAL_POLYCUBE_IGA_DECLARE_TAG)
#undef CGAL_POLYCUBE_IGA_DECLARE_TAG
} // namespace internal_np

/// Parameter pack carrying the package's options; usable wherever CGAL expects named parameters.
template <typename T, typename Tag, typename Base = CGAL::internal_np::No_property>
struct Named_parameters : CGAL::Named_function_parameters<T, Tag, Base>
{
  using CGAL::Named_function_parameters<T, Tag, Base>::Named_function_parameters;
  using self = Named_parameters<T, Tag, Base>;

#define CGAL_POLYCUBE_IGA_MEMBER(TAG, NAME)                                          \
  template <typename K>                                                             \
  Named_parameters<K, internal_np::TAG, self> NAME(const K& k) const                \
  { return Named_parameters<K, internal_np::TAG, self>(k, *this); }
  CGAL_POLYCUBE_IGA_NAMED_PARAMETERS(CGAL_POLYCUBE_IGA_MEMBER)
#undef CGAL_POLYCUBE_IGA_MEMBER
};

namespace parameters {

using CGAL::parameters::default_values;
using CGAL::parameters::Default_named_parameters;

#define CGAL_POLYCUBE_IGA_FREE_FUNCTION(TAG, NAME)                                   \
  template <typename K>                                                             \
  Named_parameters<K, internal_np::TAG> NAME(const K& k)                            \
  { return Named_parameters<K, internal_np::TAG>(k); }
CGAL_POLYCUBE_IGA_NAMED_PARAMETERS(CGAL_POLYCUBE_IGA_FREE_FUNCTION)
#undef CGAL_POLYCUBE_IGA_FREE_FUNCTION

} // namespace parameters

/// Value of option `tag` in `np`, or `fallback` when it was not given.
template <typename Tag, typename NP, typename D>
auto option(const NP& np, Tag tag, const D& fallback)
{
  return CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, tag), fallback);
}

} // namespace Polycube_IGA
} // namespace CGAL

#endif // CGAL_POLYCUBE_IGA_PARAMETERS_H
