// Products of small column-major matrices: the SVD partition's (the Newmark step's solves) and the
// exact gradients' sweeps (a handful of coordinates, closure rows, design variables or active
// constraints), where Eigen's dynamic-size product kernels and expressions spend more on choosing
// and peeling their loops than on the arithmetic (perf on BM_TramwaySimulation and
// BM_TramwayGradientAdjoint). For large chains the inner loops run down contiguous columns, which
// the compiler vectorises.
#pragma once

#include <Eigen/Core>

namespace mbsopt {

/// What a product does with the matrix it writes: C = A B, C += A B or C −= A B.
enum class Accumulate { Assign, Add, Subtract };

/// C (rows × cols) = A B, += A B or −= A B, A rows × inner and B inner × cols, all column-major on
/// raw data. Up to 8 rows the row count is a constant of the inner loops (unrolled); each column of
/// C gets the same operations in the same order whatever the number of columns.
void multiply(const double* a, const double* b, double* c, Eigen::Index rows, Eigen::Index inner, Eigen::Index cols,
              Accumulate mode);

/// C (rows × cols) = Aᵀ B, A inner × rows and B inner × cols: a dot product down two columns per
/// coefficient (dotProduct).
void multiplyTransposed(const double* a, const double* b, double* c, Eigen::Index rows, Eigen::Index inner,
                        Eigen::Index cols);

/// The same on Eigen matrices: C = A B (C resized), C += A B or C −= A B (C of the product's size).
/// C must not share storage with A or B.
void multiply(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, Eigen::MatrixXd& c,
              Accumulate mode = Accumulate::Assign);

}  // namespace mbsopt
