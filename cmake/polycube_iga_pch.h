// Heavy, stable includes shared by every program of the build (not installed).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <Eigen/Sparse>
#include <Eigen/Dense>
#include <Eigen/CholmodSupport>
