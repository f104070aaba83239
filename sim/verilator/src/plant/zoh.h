// SPDX-License-Identifier: GPL-2.0-or-later
//
// zoh.h - exact discretisation of a linear time-invariant system
//
//     x' = A x + B u
//
// with the input held constant over a step of h seconds (zero-order hold):
//
//     x[k+1] = Ad x[k] + Bd u[k],   Ad = e^(A h),   Bd = (integral_0^h e^(A s) ds) B.
//
// Both come from one matrix exponential of the augmented matrix
// [[A, B], [0, 0]] * h (its upper blocks are Ad and Bd), computed by Eigen's
// MatrixFunctions module (Pade approximation with scaling and squaring).
// For a constant input the result is the exact solution at the step times,
// so a model built on it matches the analytic step responses to rounding.
#ifndef VBOARD_PLANT_ZOH_H
#define VBOARD_PLANT_ZOH_H

#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>

namespace vb::plant {

template <int N, int M> class Zoh {
  public:
    using StateMat = Eigen::Matrix<double, N, N>;
    using InputMat = Eigen::Matrix<double, N, M>;
    using State = Eigen::Matrix<double, N, 1>;
    using Input = Eigen::Matrix<double, M, 1>;

    Zoh() : ad_(StateMat::Identity()), bd_(InputMat::Zero()) {}

    // Discretise (A, B) for steps of h seconds.
    void set(const StateMat &a, const InputMat &b, double h)
    {
        Eigen::Matrix<double, N + M, N + M> aug = Eigen::Matrix<double, N + M, N + M>::Zero();
        aug.template topLeftCorner<N, N>() = a * h;
        aug.template topRightCorner<N, M>() = b * h;
        Eigen::Matrix<double, N + M, N + M> e = aug.exp();
        ad_ = e.template topLeftCorner<N, N>();
        bd_ = e.template topRightCorner<N, M>();
    }

    State step(const State &x, const Input &u) const { return ad_ * x + bd_ * u; }

    const StateMat &ad() const { return ad_; }
    const InputMat &bd() const { return bd_; }

  private:
    StateMat ad_;
    InputMat bd_;
};

} // namespace vb::plant

#endif // VBOARD_PLANT_ZOH_H
