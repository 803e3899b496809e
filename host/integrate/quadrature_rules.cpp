#include "integrate/quadrature_rules.h"

#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/special_functions/legendre.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "brdfbake/error.h"

namespace brdfbake {

// The zeros of P_n and the weights 2/((1 - x^2) P_n'(x)^2) from Boost.Math, mapped from [-1, 1].
void append_gauss_legendre(unsigned n, std::vector<double>& out, unsigned lanes) {
    const std::vector<double> zeros = boost::math::legendre_p_zeros<double>(int(n));  // the zeros >= 0
    std::vector<std::pair<double, double>> rule;
    for (double z : zeros) {
        const double d = boost::math::legendre_p_prime(int(n), z);
        const double w = 1.0 / ((1.0 - z * z) * d * d);  // half the weight on [-1, 1]
        rule.push_back({0.5 * (1.0 + z), w});
        if (z != 0.0) rule.push_back({0.5 * (1.0 - z), w});
    }
    std::sort(rule.begin(), rule.end());
    const size_t padded = (rule.size() + lanes - 1) / lanes * lanes;
    for (const auto& r : rule) out.push_back(r.first);
    out.resize(out.size() + padded - rule.size(), 0.5);
    for (const auto& r : rule) out.push_back(r.second);
    out.resize(out.size() + padded - rule.size(), 0.0);
}

namespace {

// The (2g + 1)-point Gauss-Kronrod rule on [0, 1] and its embedded g-point Gauss rule
// [Kronrod 1965; Laurie, Math. Comp. 66, 1997], from Boost.Math. One set of nodes gives both
// sums: the Kronrod sum is the value and its distance to the Gauss sum the error estimate.
template <unsigned K>
void append_kronrod(std::vector<double>& out, unsigned lanes) {
    constexpr unsigned G = (K - 1) / 2;
    using kronrod = boost::math::quadrature::gauss_kronrod<double, K>;
    using gauss = boost::math::quadrature::gauss<double, G>;
    std::vector<std::array<double, 3>> rule;  // abscissa on [0, 1], Kronrod weight, Gauss weight
    for (size_t i = 0; i < kronrod::abscissa().size(); ++i) {
        const double z = kronrod::abscissa()[i], wk = 0.5 * kronrod::weights()[i];
        double wg = 0.0;
        for (size_t j = 0; j < gauss::abscissa().size(); ++j)
            if (std::fabs(gauss::abscissa()[j] - z) < 1e-13) wg = 0.5 * gauss::weights()[j];
        rule.push_back({0.5 * (1.0 + z), wk, wg});
        if (z != 0.0) rule.push_back({0.5 * (1.0 - z), wk, wg});
    }
    std::sort(rule.begin(), rule.end());
    const size_t padded = (rule.size() + lanes - 1) / lanes * lanes;
    for (int column = 0; column < 3; ++column) {
        for (const auto& r : rule) out.push_back(r[column]);
        out.resize(out.size() + padded - rule.size(), column == 0 ? 0.5 : 0.0);
    }
}

}  // namespace

void append_gauss_kronrod(unsigned points, std::vector<double>& out, unsigned lanes) {
    switch (points) {
        case 15: return append_kronrod<15>(out, lanes);
        case 21: return append_kronrod<21>(out, lanes);
        case 31: return append_kronrod<31>(out, lanes);
        case 41: return append_kronrod<41>(out, lanes);
        case 51: return append_kronrod<51>(out, lanes);
        case 61: return append_kronrod<61>(out, lanes);
    }
    throw Error("internal error: no " + std::to_string(points) + "-point Gauss-Kronrod rule");
}

// For an integrand that is smooth on the domain the Gauss-Legendre error falls geometrically,
// e(n) ~ r^(2n): the difference d1 = |Q(n) - Q(n/2)| ~ e(n/2) is then about the square of
// d2 = |Q(n/2) - Q(n/4)| (relative to the integral), and d1 bounds e(n) with a wide margin.
// Where it is not (a kink, such as Torrance-Sparrow's V-groove min(), or a feature the rules do
// not yet resolve), the error falls algebraically or erratically and d1 can be far below e(n)
// (22x measured at mu = 1e-4): then the larger of the two differences is taken. Torrance-
// Sparrow's integrand always has the kink, and at grazing its rules can agree at 8, 16 and 32
// nodes on a value 2.5e-5 off (n = 6, mu = 1e-4) before they resolve it: for it the larger
// difference is always taken.
double quadrature_error(double fine, double coarse, double coarsest, bool kinked) {
    const double scale = std::max(std::fabs(fine), 1e-3);
    const double d1 = std::fabs(fine - coarse) / scale, d2 = std::fabs(coarse - coarsest) / scale;
    const bool geometric = !kinked && d1 <= std::pow(d2, 1.5);
    return scale * (geometric ? d1 : std::max(d1, d2));
}

unsigned quadrature_order(std::uint64_t samples) {
    const double n = std::sqrt(double(samples) / 4.0);
    unsigned order = 2 * unsigned(std::lround(n / 2.0));
    return std::clamp(order, 4u, 4096u);
}

}  // namespace brdfbake
