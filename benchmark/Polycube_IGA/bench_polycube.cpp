// Copyright (c) 2026 Polycube_IGA contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Suite `polycube`: the polycube map of every closed test and benchmark mesh (and two shared
// CAD meshes), as the cuboid decomposition makes it (internal::polycube_map_attempt()).
// Stages timed (best of --repetitions, wall clock, one core), on the mesh in memory:
//   nearest  the map on the nearest labels alone (internal::polycube_map_on_labels() at
//            border weight 0), what every map costs
//   map      the whole attempt: the nearest labels, then, when those make no polycube,
//            graph-cut labels at border weights 0.01 and 0.02; map / nearest is what the
//            graph cuts add to a refused map
// Fields: polycube (1 when the attempt makes one), label_border_weight (0: the nearest
// labels), charts, and the faces the deformation turns over on the nearest labels and on
// the attempt's (the nearest labels' again when it is refused). Baseline, same mesh, same
// run: one CHOLMOD supernodal factorization and one solve of L + 1e-8 M (bench_meshes.h).
//
//   build/bin/polycube_iga_benchmark polycube            # every closed mesh (about 6 minutes)
//   build/bin/polycube_iga_benchmark --quick polycube    # those under 2,000 faces

#include "bench_meshes.h"

#include <CGAL/Polycube_IGA/internal/polycube_map.h>
#include <CGAL/boost/graph/helpers.h>

#include <string>
#include <vector>

namespace polycube_iga_bench {
namespace {

namespace PI = CGAL::Polycube_IGA;
using meshes::Mesh;

// "test:" + test data name, "bench:" + benchmark data name, else relative to the shared data.
const char* const files[] = {
  "test:3holes.obj", "test:3torus.off", "test:anchor.off", "test:chain5.off", "test:chain6.off", "test:cube-meshed.off",
  "test:double-torus-example.off", "test:eight.off", "test:elephant.off", "test:femur.off", "test:joint.off",
  "test:joint_remeshed.off", "test:knot.off", "test:pipe.off", "test:plate5.off", "test:plate6.off",
  "test:plate_two_round_holes.off", "test:plate_two_round_holes_remeshed.off", "test:ring4.off", "test:ring5.off",
  "test:rotor.off", "test:sphere.off", "test:square_ring.off", "test:t_block_filleted.off",
  "test:t_block_filleted_remeshed.off", "test:torus.obj", "test:wheel3.off",
  "bench:cad_L_bracket_2holes.off", "bench:cad_box_3holes.off", "bench:cad_cube_cross_holes.off",
  "bench:cad_elbow_tube.off", "bench:cad_flange_5holes.off", "bench:cad_flanged_bushing.off",
  "bench:cad_mug_torus_handle.off", "bench:cad_plate_6holes.off", "bench:cad_pulley_vgroove.off",
  "bench:cad_spoked_wheel.off", "bench:cad_stepped_shaft.off", "bench:cad_tee_solid.off", "bench:org_banana.off",
  "bench:org_blobby_4limbs.off", "bench:org_plate_4holes.off", "bench:org_plate_6holes.off",
  "bench:org_pretzel_genus2.off", "bench:org_quad_torus_genus4.off", "bench:org_triple_torus_genus3.off",
  "bench:org_twisted_torus.off", "cgal/fandisk.off", "cgal/anchor_dense.off",
};

void run_case(const Options& opt, const std::string& file)
{
  const bool in_tests = file.rfind("test:", 0) == 0, in_bench = file.rfind("bench:", 0) == 0;
  const std::string path = in_tests   ? std::string(POLYCUBE_IGA_TEST_DATA_DIR) + "/" + file.substr(5)
                           : in_bench ? std::string(POLYCUBE_IGA_BENCH_DATA_DIR) + "/" + file.substr(6)
                                      : opt.data_dir + "/" + file;
  const std::string name = meshes::base_name(path);
  Mesh mesh;
  if(!meshes::read_subdivided(path, 0, mesh)) {
    std::cerr << "polycube: skipping " << path << ": cannot read it\n";
    return;
  }
  if(!CGAL::is_closed(mesh)) return; // a polycube map needs a closed surface
  if(opt.quick && num_faces(mesh) >= 2000) return;

  using Attempt = PI::internal::Polycube_map_attempt<typename Mesh::Point>;
  Attempt nearest, attempt;
  const double t_nearest = best_time(opt.repetitions, [&] {
    const auto [normal, area] = PI::internal::face_normals_and_areas(mesh);
    const Eigen::Matrix3d frame = PI::internal::polycube_frame(mesh, normal, area);
    nearest = PI::internal::polycube_map_on_labels(mesh, frame, normal, area, 0.);
  });
  const double t_map = best_time(opt.repetitions, [&] { attempt = PI::internal::polycube_map_attempt(mesh); });

  double t_assembly = 0, residual = 0;
  const double t_baseline = meshes::cholmod_laplacian_baseline(mesh, opt.repetitions, t_assembly, residual);
  if(residual > 1e-8) std::cerr << "polycube: " << name << ": baseline residual " << residual << "\n";

  std::vector<std::pair<std::string, double>> extra = {
    {"faces", double(num_faces(mesh))},
    {"polycube", attempt.position ? 1.0 : 0.0},
    {"label_border_weight", attempt.border_weight},
    {"charts", double(attempt.charts)},
    {"turned_nearest", double(nearest.faces_turned())},
    {"turned", double(attempt.faces_turned())},
    {"threads", 1.0},
  };
  std::vector<std::pair<std::string, double>> stages = {{"nearest", t_nearest}, {"map", t_map}};
  char label[96];
  std::snprintf(label, sizeof(label), "%s (%zuf)", name.c_str(), std::size_t(num_faces(mesh)));
  report("polycube", label, extra, stages, "cholmod", t_baseline);
}

void run_suite(const Options& opt)
{
  meshes::One_core core;
  meshes::print_timed_suite_header("polycube", opt, core);
  for(const char* file : files) run_case(opt, file);
}

static Register_suite polycube_suite("polycube", run_suite);

} // namespace
} // namespace polycube_iga_bench
