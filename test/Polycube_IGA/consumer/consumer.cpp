// Uses the installed headers: solves a tiny SPD system through the package's CHOLMOD
// wrapper, so that a broken include path or a missing CHOLMOD link fails the test.
#include <CGAL/Polycube_IGA/Errors.h>
#include <CGAL/Polycube_IGA/internal/sparse_cholesky.h>
#include <iostream>

int main()
{
  Eigen::SparseMatrix<double> A(2, 2);
  A.insert(0, 0) = 4; A.insert(1, 1) = 2; A.insert(1, 0) = 1; A.insert(0, 1) = 1;
  A.makeCompressed();
  CGAL::Polycube_IGA::internal::Sparse_cholesky chol;
  chol.factor(A);
  Eigen::VectorXd b(2); b << 1, 2;
  Eigen::MatrixXd x = chol.solve(b);
  const double r = (A * x.col(0) - b).norm();
  std::cout << "residual " << r << "\n";
  return r < 1e-12 ? 0 : 1;
}
