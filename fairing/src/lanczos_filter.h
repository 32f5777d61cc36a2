// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The filter_implicit_fairing authors
// Implicit steps applied through a Lanczos tridiagonal matrix T_k (Golub & Meurant, "Matrices,
// Moments and Quadrature"): shared by the automatic strength (auto_strength.h), which evaluates
// the filter for many time steps, and the frozen-operator steps (frozen_steps.h), which apply it
// once (not installed).
//
// Conventions: T_k has diagonal a[0..k-1] and off-diagonal b (b[j] joins j and j + 1; only
// b[0..k-2] are read). With w_0 = e1 and w_j = (I + lambda T^p)^-1 w_{j-1}, the result is
// lambda sum_{j=1..s} w_j: the coefficients of the Lanczos vectors in x_0 - x_s per unit start
// vector. p = 1: I + lambda T is symmetric positive definite. p >= 2 (T the first-order G1 of an
// L^p step, the paper's section 2.6 and Figure 3a) by partial fractions over the roots of
// 1 + lambda g^p: with c = lambda^(1/p) and theta_m = pi (2m + 1) / p,
//   (1 + lambda g^p)^-1 = (1/p) sum_{m=0..p-1} (1 + sigma_m g)^-1,   sigma_m = -c e^(-i theta_m)
// (each root g_m = e^(i theta_m) / c contributes 1 / (p'(g_m) (g - g_m)) = (1/p) / (1 - g/g_m)).
// The roots come in conjugate pairs, so for real w the sum is (2/p) Re over the pairs with
// theta_m < pi, plus (1/p) times the real solve with sigma = c when p is odd; p = 2 is the single
// pair sigma = i sqrt(lambda): Re (I + i sqrt(lambda) T)^-1. Each I + sigma T is complex
// symmetric, and e^(-i psi) (I + sigma T) has a positive definite real part for some psi (arg
// sigma < pi), so every leading block is nonsingular and none needs pivoting; each is factored
// once (LDL') for all s steps.
#pragma once

#include <cmath>
#include <complex>
#include <vector>

namespace fairing {
namespace detail {

namespace lanczos_filter_impl {

// A real pivot of an SPD matrix is positive; rounding must not make it 0 at huge lambda.
inline void floor_pivot(double& p) { p = p > 1e-300 ? p : 1e-300; }
inline void floor_pivot(std::complex<double>&) {}

template <class S>
void factor(const std::vector<double>& a, const std::vector<double>& b, int k, S sigma,
            std::vector<S>& pivot, std::vector<S>& upper) {
    pivot.assign(k, S(0));
    upper.assign(k, S(0));
    for (int i = 0; i < k; ++i) {
        const S off = i > 0 ? sigma * b[i - 1] : S(0);
        pivot[i] = S(1) + sigma * a[i] - (i > 0 ? off * upper[i - 1] : S(0));
        floor_pivot(pivot[i]);
        upper[i] = i + 1 < k ? sigma * b[i] / pivot[i] : S(0);
    }
}

template <class S>
void solve(const std::vector<double>& b, S sigma, const std::vector<S>& pivot,
           const std::vector<S>& upper, std::vector<S>& w) {
    const int k = static_cast<int>(w.size());
    for (int i = 0; i < k; ++i)  // forward: L z = w
        w[i] = (w[i] - (i > 0 ? sigma * b[i - 1] * w[i - 1] : S(0))) / pivot[i];
    for (int i = k - 2; i >= 0; --i) w[i] -= upper[i] * w[i + 1];  // back: L' x = z
}

}  // namespace lanczos_filter_impl

// kept (optional): e1' w_s, the Gauss quadrature of e1' h(T) e1. partial (optional): the sums
// after steps 1..s-1 are appended. power: p above (1 or more).
inline std::vector<double> implicit_steps_filter(const std::vector<double>& a,
                                                 const std::vector<double>& b, int k,
                                                 double lambda, int steps, int power,
                                                 double* kept = nullptr,
                                                 std::vector<std::vector<double>>* partial =
                                                     nullptr) {
    using namespace lanczos_filter_impl;
    std::vector<double> w(k, 0.0), sum(k, 0.0);
    if (kept) *kept = 0;
    if (k == 0) return sum;
    w[0] = 1;
    if (power == 2) {
        using Complex = std::complex<double>;
        const Complex sigma(0, std::sqrt(lambda));
        std::vector<Complex> pivot, upper, z(k);
        factor(a, b, k, sigma, pivot, upper);
        for (int step = 1; step <= steps; ++step) {
            for (int i = 0; i < k; ++i) z[i] = w[i];
            solve(b, sigma, pivot, upper, z);
            for (int i = 0; i < k; ++i) sum[i] += lambda * (w[i] = z[i].real());
            if (partial && step < steps) partial->push_back(sum);
        }
    } else if (power > 2) {
        using Complex = std::complex<double>;
        const double pi = 3.14159265358979323846;
        const double c = std::pow(lambda, 1.0 / power);
        const int pairs = power / 2;
        std::vector<Complex> sigma(pairs);
        std::vector<std::vector<Complex>> pivot(pairs), upper(pairs);
        for (int m = 0; m < pairs; ++m) {
            sigma[m] = -c * std::polar(1.0, -pi * (2 * m + 1) / power);
            factor(a, b, k, sigma[m], pivot[m], upper[m]);
        }
        std::vector<double> real_pivot, real_upper, y(k);
        if (power % 2) factor(a, b, k, c, real_pivot, real_upper);
        std::vector<Complex> z(k);
        for (int step = 1; step <= steps; ++step) {
            for (int i = 0; i < k; ++i) y[i] = 0;
            for (int m = 0; m < pairs; ++m) {
                for (int i = 0; i < k; ++i) z[i] = w[i];
                solve(b, sigma[m], pivot[m], upper[m], z);
                for (int i = 0; i < k; ++i) y[i] += 2 * z[i].real();
            }
            if (power % 2) {
                std::vector<double> r(w);
                solve(b, c, real_pivot, real_upper, r);
                for (int i = 0; i < k; ++i) y[i] += r[i];
            }
            for (int i = 0; i < k; ++i) sum[i] += lambda * (w[i] = y[i] / power);
            if (partial && step < steps) partial->push_back(sum);
        }
    } else {
        std::vector<double> pivot, upper;
        factor(a, b, k, lambda, pivot, upper);
        for (int step = 1; step <= steps; ++step) {
            solve(b, lambda, pivot, upper, w);
            for (int i = 0; i < k; ++i) sum[i] += lambda * w[i];
            if (partial && step < steps) partial->push_back(sum);
        }
    }
    if (kept) *kept = w[0];
    return sum;
}

}  // namespace detail
}  // namespace fairing
