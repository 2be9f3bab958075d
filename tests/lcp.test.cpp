// The LCP solvers (solve/lcp.hpp) against brute-force enumeration of all complementary index sets on random
// P-matrices (exactly one solution each), their failure statuses, and the joint stick/slip resolution of contacts at
// rest (Pfeiffer & Glocker): against enumeration of all 3^n stick/slip sets, on two coupled contacts where deciding
// contact by contact gives an inconsistent set, and in its one-contact case, Leine's switch model.
#include <cmath>
#include <cstddef>
#include <limits>
#include <random>
#include <vector>

#include <frictionsim/contact/switching.hpp>
#include <frictionsim/friction/coulomb.hpp>
#include <frictionsim/contact/lcp.hpp>

#include "catch.hpp"
#include "rejection.hpp"

using namespace frictionsim;

namespace {

using Matrix = std::vector<double>;  // row-major

/// Solves A x = b by Gauss-Jordan with full pivoting (independent of lcp.hpp's elimination); false if singular.
bool gauss_jordan(std::vector<std::vector<double>> A, std::vector<double>& b) {
    const std::size_t m = b.size();
    std::vector<std::size_t> col(m);
    for (std::size_t i = 0; i < m; ++i) col[i] = i;
    for (std::size_t k = 0; k < m; ++k) {
        std::size_t pr = k, pc = k;
        for (std::size_t i = k; i < m; ++i)
            for (std::size_t j = k; j < m; ++j)
                if (std::abs(A[i][j]) > std::abs(A[pr][pc])) pr = i, pc = j;
        if (std::abs(A[pr][pc]) < 1e-13) return false;
        std::swap(A[k], A[pr]);
        std::swap(b[k], b[pr]);
        for (auto& row : A) std::swap(row[k], row[pc]);
        std::swap(col[k], col[pc]);
        for (std::size_t i = 0; i < m; ++i) {
            if (i == k) continue;
            const double f = A[i][k] / A[k][k];
            for (std::size_t j = k; j < m; ++j) A[i][j] -= f * A[k][j];
            b[i] -= f * b[k];
        }
    }
    std::vector<double> x(m);
    for (std::size_t k = 0; k < m; ++k) x[col[k]] = b[k] / A[k][k];
    b = x;
    return true;
}

/// Every solution of LCP(M, q), by trying all 2^n complementary index sets.
std::vector<std::vector<double>> all_solutions(const Matrix& M, const std::vector<double>& q) {
    const std::size_t n = q.size();
    std::vector<std::vector<double>> found;
    for (unsigned set = 0; set < (1u << n); ++set) {
        std::vector<std::size_t> B;
        for (std::size_t i = 0; i < n; ++i)
            if (set & (1u << i)) B.push_back(i);
        std::vector<std::vector<double>> A(B.size(), std::vector<double>(B.size()));
        std::vector<double> rhs(B.size());
        for (std::size_t i = 0; i < B.size(); ++i) {
            rhs[i] = -q[B[i]];
            for (std::size_t j = 0; j < B.size(); ++j) A[i][j] = M[B[i] * n + B[j]];
        }
        if (!gauss_jordan(A, rhs)) continue;
        std::vector<double> z(n, 0.0);
        for (std::size_t i = 0; i < B.size(); ++i) z[B[i]] = rhs[i];
        bool ok = true;
        for (std::size_t i = 0; i < n && ok; ++i) {
            double w = q[i];
            for (std::size_t j = 0; j < n; ++j) w += M[i * n + j] * z[j];
            ok = z[i] >= -1e-10 && w >= -1e-10;
        }
        if (ok) found.push_back(z);
    }
    return found;
}

/// A random P-matrix: S + K with S symmetric positive definite and K skew-symmetric (x'Mx = x'Sx > 0).
Matrix random_p_matrix(std::size_t n, std::mt19937& rng) {
    std::normal_distribution<double> g(0.0, 1.0);
    Matrix A(n * n), M(n * n, 0.0);
    for (double& a : A) a = g(rng);
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j) {
            double s = (i == j) ? 0.1 : 0.0;
            for (std::size_t k = 0; k < n; ++k) s += A[i * n + k] * A[j * n + k];
            M[i * n + j] = s;
        }
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j) {
            const double k = g(rng);
            M[i * n + j] += k;
            M[j * n + i] -= k;
        }
    return M;
}

void check_complementary(const LcpSolution& s, double tol) {
    for (std::size_t i = 0; i < s.z.size(); ++i) {
        CHECK(s.z[i] >= 0.0);
        CHECK(s.w[i] >= -tol);
        CHECK(std::abs(s.z[i] * s.w[i]) <= tol);
    }
}

/// Is the stick/slip set `modes` consistent (a = W lambda + b; stick: a = 0 and |lambda| <= L; slip +-: lambda = -+L
/// and a of that sign)? Fills lambda. Independent of lcp.hpp: solves the stuck contacts' equations directly.
bool consistent(const Matrix& W, const std::vector<double>& b, const std::vector<double>& L, const std::vector<int>& modes,
                std::vector<double>& lambda) {
    const std::size_t n = b.size();
    lambda.assign(n, 0.0);
    std::vector<std::size_t> S;
    for (std::size_t i = 0; i < n; ++i) {
        if (modes[i] == 0) S.push_back(i);
        else lambda[i] = -modes[i] * L[i];
    }
    std::vector<std::vector<double>> A(S.size(), std::vector<double>(S.size()));
    std::vector<double> rhs(S.size());
    for (std::size_t r = 0; r < S.size(); ++r) {
        rhs[r] = -b[S[r]];
        for (std::size_t i = 0; i < n; ++i)
            if (modes[i] != 0) rhs[r] -= W[S[r] * n + i] * lambda[i];
        for (std::size_t c = 0; c < S.size(); ++c) A[r][c] = W[S[r] * n + S[c]];
    }
    if (!gauss_jordan(A, rhs)) return false;
    for (std::size_t r = 0; r < S.size(); ++r) lambda[S[r]] = rhs[r];
    for (std::size_t i = 0; i < n; ++i) {
        double a = b[i];
        for (std::size_t j = 0; j < n; ++j) a += W[i * n + j] * lambda[j];
        if (modes[i] == 0 && std::abs(lambda[i]) > L[i] * (1.0 + 1e-12)) return false;
        if (modes[i] != 0 && !(modes[i] * a > 0.0)) return false;
    }
    return true;
}

}  // namespace

TEST_CASE("LCP: Lemke and Murty find the one solution of random P-matrix problems", "[lcp]") {
    std::mt19937 rng(20071);
    std::normal_distribution<double> g(0.0, 1.0);
    int checked = 0;
    for (std::size_t n = 1; n <= 6; ++n)
        for (int trial = 0; trial < 40; ++trial) {
            const Matrix M = random_p_matrix(n, rng);
            std::vector<double> q(n);
            for (double& v : q) v = 2.0 * g(rng);
            const auto reference = all_solutions(M, q);
            REQUIRE(reference.size() == 1);  // P-matrix: exactly one
            const LcpSolution lemke = solve_lcp_lemke(M, q), murty = solve_lcp_murty(M, q);
            REQUIRE(lemke.solved());
            REQUIRE(murty.solved());
            for (std::size_t i = 0; i < n; ++i) {
                CHECK(lemke.z[i] == Approx(reference[0][i]).margin(1e-9));
                CHECK(murty.z[i] == Approx(reference[0][i]).margin(1e-9));
            }
            check_complementary(lemke, 1e-9);
            check_complementary(murty, 1e-9);
            ++checked;
        }
    CHECK(checked == 240);
}

TEST_CASE("LCP: trivial and degenerate problems", "[lcp]") {
    const Matrix M{2.0, 1.0, 1.0, 2.0};
    const LcpSolution zero = solve_lcp(M, {1.0, 0.0});  // q >= 0: z = 0
    REQUIRE(zero.solved());
    CHECK(zero.z == std::vector<double>{0.0, 0.0});
    CHECK(zero.pivots == 0);
    // degenerate: q = (-1, -1) with M = [[1, 1], [1, 1]] has solutions on a segment z1 + z2 = 1
    const LcpSolution tie = solve_lcp_lemke({1.0, 1.0, 1.0, 1.0}, {-1.0, -1.0});
    REQUIRE(tie.solved());
    CHECK(tie.z[0] + tie.z[1] == Approx(1.0));
    check_complementary(tie, 1e-12);
}

TEST_CASE("LCP: an infeasible problem ends in a ray, a non-P-matrix is reported, bad input is rejected", "[lcp]") {
    // w = -z - 1 >= 0 has no z >= 0: Lemke's secondary ray
    const LcpSolution ray = solve_lcp_lemke({-1.0}, {-1.0});
    CHECK(ray.status == LcpStatus::ray_termination);
    CHECK_FALSE(ray.solved());
    // Murty's method on the same (not a P-matrix) cycles between the two index sets: a status, not a hang
    const LcpSolution murty = solve_lcp_murty({-1.0}, {-1.0});
    CHECK_FALSE(murty.solved());
    CHECK(std::string(lcp_status_name(murty.status)) != "solved");
    // a singular principal block
    CHECK(solve_lcp_murty({0.0}, {-1.0}).status == LcpStatus::singular_pivot);
    const double nan_value = std::numeric_limits<double>::quiet_NaN();
    CHECK(rejected_parameter([&] { solve_lcp({1.0, nan_value, 0.0, 1.0}, {1.0, -1.0}); }) == "M");
    CHECK(rejected_parameter([&] { solve_lcp_murty({1.0}, {std::numeric_limits<double>::infinity()}); }) == "q");
    CHECK(rejected_parameter([] { solve_lcp({1.0, 0.0}, {1.0, -1.0}); }) == "M");
}

TEST_CASE("Contacts at rest: the joint LCP gives the one consistent stick/slip set of all 3^n", "[lcp]") {
    std::mt19937 rng(2004);
    std::normal_distribution<double> g(0.0, 1.0);
    std::uniform_real_distribution<double> u(0.2, 2.0);
    for (std::size_t n = 1; n <= 4; ++n)
        for (int trial = 0; trial < 50; ++trial) {
            Matrix A(n * n), W(n * n, 0.0);  // W = A A' + 0.05 I: an inverse mass seen by n coupled contacts
            for (double& a : A) a = g(rng);
            for (std::size_t i = 0; i < n; ++i)
                for (std::size_t j = 0; j < n; ++j) {
                    double s = i == j ? 0.05 : 0.0;
                    for (std::size_t k = 0; k < n; ++k) s += A[i * n + k] * A[j * n + k];
                    W[i * n + j] = s;
                }
            std::vector<double> b(n), L(n);
            for (std::size_t i = 0; i < n; ++i) {
                L[i] = u(rng);
                b[i] = 2.0 * g(rng) * W[i * n + i] * L[i];
            }
            // enumerate every stick/slip set
            std::vector<std::vector<int>> sets;
            std::vector<double> lambda, reference_lambda;
            std::size_t total = 1;
            for (std::size_t i = 0; i < n; ++i) total *= 3;
            for (std::size_t code = 0; code < total; ++code) {
                std::vector<int> modes(n);
                std::size_t c = code;
                for (std::size_t i = 0; i < n; ++i, c /= 3) modes[i] = static_cast<int>(c % 3) - 1;
                if (consistent(W, b, L, modes, lambda)) {
                    sets.push_back(modes);
                    reference_lambda = lambda;
                }
            }
            REQUIRE(sets.size() == 1);  // W positive definite: the box problem is a strictly convex QP, one solution
            const ContactsAtRest joint = resolve_contacts_at_rest(W, b, L);
            REQUIRE(joint.solved());
            CHECK(joint.modes == sets[0]);
            for (std::size_t i = 0; i < n; ++i) CHECK(joint.friction[i] == Approx(reference_lambda[i]).margin(1e-9));
        }
}

TEST_CASE("Contacts at rest: two coupled contacts, contact by contact is inconsistent, jointly both stick", "[lcp]") {
    // Two contacts strongly coupled through the mechanism (W12 = 0.9 W11), both pushed forwards. Each alone would
    // need |b_i / W_ii| = 1.5 > L_i = 1 to stick, so deciding contact by contact makes both slip forwards, with
    // friction -L each, and then both accelerations are negative: a contradiction. Jointly both stick, each
    // holding 1.5 / 1.9 < 1.
    const Matrix W{1.0, 0.9, 0.9, 1.0};
    const std::vector<double> b{1.5, 1.5}, L{1.0, 1.0};
    std::vector<int> by_contact(2);
    for (std::size_t i = 0; i < 2; ++i) by_contact[i] = std::abs(b[i] / W[i * 2 + i]) <= L[i] ? 0 : (b[i] > 0 ? 1 : -1);
    CHECK(by_contact == std::vector<int>{1, 1});
    std::vector<double> lambda;
    CHECK_FALSE(consistent(W, b, L, by_contact, lambda));
    const double a0 = b[0] + W[0] * (-L[0]) + W[1] * (-L[1]);
    CHECK(a0 < 0.0);  // slipping forwards while decelerating backwards

    const ContactsAtRest joint = resolve_contacts_at_rest(W, b, L);
    REQUIRE(joint.solved());
    CHECK(joint.modes == std::vector<int>{0, 0});
    CHECK(joint.friction[0] == Approx(-1.5 / 1.9).epsilon(1e-12));
    CHECK(joint.friction[1] == Approx(-1.5 / 1.9).epsilon(1e-12));
    CHECK(joint.acceleration == std::vector<double>{0.0, 0.0});
    CHECK(consistent(W, b, L, joint.modes, lambda));
}

TEST_CASE("Contacts at rest: one contact is Leine's switch model (ContactSwitching)", "[lcp]") {
    std::mt19937 rng(1999);
    std::uniform_real_distribution<double> mass(0.1, 10.0), accel(-20.0, 20.0), normal(1.0, 100.0);
    const Coulomb law(0.3, 0.45);
    int sticks = 0, slips = 0;
    for (int trial = 0; trial < 500; ++trial) {
        const double m = mass(rng), b = accel(rng), N = normal(rng);
        const double stick_force = m * b;  // the friction force that holds the contact (a = b - F / m)
        bool stop = false;
        const int fired[2] = {-1, 0};
        const int leine = ContactSwitching<Coulomb>::switch_mode(law, N, slip_positive, fired, stick_force, stop);
        const ContactsAtRest lcp = resolve_contacts_at_rest({1.0 / m}, {b}, {law.static_limit(N)});
        REQUIRE(lcp.solved());
        CHECK(lcp.modes[0] == leine);
        if (leine == stick) {
            ++sticks;
            CHECK(lcp.friction[0] == Approx(-stick_force).epsilon(1e-12));
        } else {
            ++slips;
            CHECK(lcp.friction[0] == -leine * law.static_limit(N));
            CHECK(lcp.acceleration[0] * leine > 0.0);
        }
    }
    CHECK(sticks > 50);
    CHECK(slips > 50);
    // the tie: the holding force exactly at the bound. The acceleration-level problem sticks with zero reserve;
    // only the holding force's rate can tell (see rigs/navarro_lopez.hpp's exact break-away).
    const ContactsAtRest tie = resolve_contacts_at_rest({0.5}, {0.5 * 3.0}, {3.0});
    CHECK(tie.modes[0] == stick);
    CHECK(tie.friction[0] == -3.0);
    CHECK(tie.acceleration[0] == 0.0);
    CHECK(rejected_parameter([] { resolve_contacts_at_rest({1.0}, {1.0}, {0.0}); }) == "static_limit");
    CHECK(rejected_parameter([] { resolve_contacts_at_rest({1.0, 0.0}, {1.0}, {1.0}); }) == "W");
    CHECK(rejected_parameter([] { resolve_contacts_at_rest({0.0}, {1.0}, {1.0}); }) == "W");
    CHECK(rejected_parameter([] {
              resolve_contacts_at_rest({1.0}, {std::numeric_limits<double>::quiet_NaN()}, {1.0});
          }) == "free_acceleration");
}
