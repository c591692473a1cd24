// Times CHOLMOD's simplicial LDL' and Eigen's SimplicialLDLT (both with AMD) on a symmetric
// Matrix Market matrix (lower triangle, as Folio's kkt_report exports it) and a right-hand
// side (Matrix Market array): analysis, numeric factorization and solve, median of REPS
// calls each, first with the peer's own AMD, then with Folio's permutation (PERM, as
// kkt_report --perm writes it). One tab-separated line per run: solver, ordering, analysis
// us, numeric factor us, solve us, nnz(L) strictly lower, relative residual
// ||b - Kx||inf / ||b||inf, status.
//
// Build and run: see run.sh. Usage: peers MATRIX.mtx RHS.mtx PERM REPS
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <suitesparse/cholmod.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

struct Entry {
    int row, col;
    double value;
};

// Reads the lower triangle of a `coordinate real symmetric` file (0-based entries).
static std::vector<Entry> read_matrix(const char* path, int& n) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(std::string("cannot open ") + path);
    std::string line;
    std::getline(in, line);
    if (line.find("coordinate real symmetric") == std::string::npos)
        throw std::runtime_error(std::string(path) + ": not coordinate real symmetric");
    while (std::getline(in, line) && line[0] == '%') {}
    int m = 0;
    long nnz = 0;
    std::istringstream(line) >> n >> m >> nnz;
    std::vector<Entry> entries(nnz);
    for (auto& e : entries) {
        if (!(in >> e.row >> e.col >> e.value)) throw std::runtime_error("short matrix file");
        --e.row;
        --e.col;
        if (e.row < e.col) std::swap(e.row, e.col);  // keep the lower triangle
    }
    return entries;
}

// Reads a Matrix Market `array real general` column of n values.
static std::vector<double> read_rhs(const char* path, int n) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(std::string("cannot open ") + path);
    std::string line;
    while (std::getline(in, line) && line[0] == '%') {}
    int rows = 0, cols = 0;
    std::istringstream(line) >> rows >> cols;
    if (rows != n || cols != 1) throw std::runtime_error("right-hand side size mismatch");
    std::vector<double> b(n);
    for (auto& v : b)
        if (!(in >> v)) throw std::runtime_error("short right-hand side file");
    return b;
}

// Reads a permutation perm[new] = old, one a line, and the ordering's name from its first
// comment ("% Folio NAME ordering ...") into `name`.
static std::vector<int> read_perm(const char* path, int n, std::string& name) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(std::string("cannot open ") + path);
    std::string line;
    std::vector<int> perm;
    while (std::getline(in, line)) {
        if (line.rfind("% Folio ", 0) == 0 && name.empty())
            name = "Folio's " + line.substr(8, line.find(' ', 8) - 8);
        else if (!line.empty() && line[0] != '%')
            perm.push_back(std::stoi(line));
    }
    if (static_cast<int>(perm.size()) != n) throw std::runtime_error("permutation size mismatch");
    return perm;
}

// The permutation handed to Eigen by GivenOrdering.
static std::vector<int> given_perm;

// An Eigen ordering returning `given_perm` (Eigen's ordering output P^-1 maps new to old).
template <typename StorageIndex>
struct GivenOrdering {
    using PermutationType = Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, StorageIndex>;
    template <typename MatrixType>
    void operator()(const MatrixType&, PermutationType& perm) {
        perm.resize(static_cast<Eigen::Index>(given_perm.size()));
        for (size_t k = 0; k < given_perm.size(); ++k) perm.indices()[k] = given_perm[k];
    }
};

// Median wall time of `reps` calls of `f` (after one untimed call), in microseconds.
template <class F>
static double median_us(int reps, F f) {
    f();
    std::vector<double> t(reps);
    for (auto& ti : t) {
        auto start = std::chrono::steady_clock::now();
        f();
        ti = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start)
                 .count();
    }
    std::sort(t.begin(), t.end());
    return t[t.size() / 2];
}

// ||b - K x||inf / ||b||inf with K given by its lower triangle.
static double residual(const std::vector<Entry>& k, const std::vector<double>& b,
                       const double* x) {
    std::vector<double> r(b);
    for (const auto& e : k) {
        r[e.row] -= e.value * x[e.col];
        if (e.row != e.col) r[e.col] -= e.value * x[e.row];
    }
    double rn = 0, bn = 0;
    for (size_t i = 0; i < b.size(); ++i) {
        if (std::isnan(r[i])) return NAN;
        rn = std::max(rn, std::fabs(r[i]));
        bn = std::max(bn, std::fabs(b[i]));
    }
    return rn / bn;
}

static void print(const char* solver, const char* ordering, double analysis, double factor,
                  double solve, long nnz_l, double res, const std::string& status) {
    std::printf("%s\t%s\t%.1f\t%.1f\t%.1f\t%ld\t%.1e\t%s\n", solver, ordering, analysis,
                factor, solve, nnz_l, res, status.c_str());
}

// CHOLMOD with its AMD (perm empty) or with `perm`, kept as given (no postorder).
static void cholmod(const std::vector<Entry>& k, const std::vector<double>& rhs, int n,
                    int reps, std::vector<int> perm, const std::string& name) {
    cholmod_common c;
    cholmod_start(&c);
    c.print = 0;                        // zero pivots are reported in the status column
    c.supernodal = CHOLMOD_SIMPLICIAL;  // CHOLMOD's supernodal factor is LL' only
    c.final_ll = 0;                     // keep LDL'
    c.nmethods = 1;                     // one ordering (the default may also try METIS)
    c.method[0].ordering = perm.empty() ? CHOLMOD_AMD : CHOLMOD_GIVEN;
    c.postorder = perm.empty();
    int* p = perm.empty() ? nullptr : perm.data();
    cholmod_triplet* t = cholmod_allocate_triplet(n, n, k.size(), -1, CHOLMOD_REAL, &c);
    auto* ti = static_cast<int*>(t->i);
    auto* tj = static_cast<int*>(t->j);
    auto* tx = static_cast<double*>(t->x);
    for (size_t s = 0; s < k.size(); ++s) {
        ti[s] = k[s].row;
        tj[s] = k[s].col;
        tx[s] = k[s].value;
    }
    t->nnz = k.size();
    cholmod_sparse* a = cholmod_triplet_to_sparse(t, k.size(), &c);
    cholmod_dense* b = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &c);
    std::copy(rhs.begin(), rhs.end(), static_cast<double*>(b->x));

    double analysis = median_us(reps, [&] {
        cholmod_factor* l = cholmod_analyze_p(a, p, nullptr, 0, &c);
        cholmod_free_factor(&l, &c);
    });
    cholmod_factor* l = cholmod_analyze_p(a, p, nullptr, 0, &c);
    double lnz = c.lnz;  // includes the diagonal
    double factor = median_us(reps, [&] { cholmod_factorize(a, l, &c); });
    std::string status = c.status == CHOLMOD_OK
                             ? "ok"
                             : "zero pivot at column " + std::to_string(l->minor);
    cholmod_dense* x = nullptr;
    double solve = median_us(reps, [&] {
        cholmod_free_dense(&x, &c);
        x = cholmod_solve(CHOLMOD_A, l, b, &c);
    });
    double res = residual(k, rhs, static_cast<double*>(x->x));
    print("CHOLMOD simplicial LDL'", p ? name.c_str() : "AMD (CHOLMOD)", analysis, factor,
          solve, static_cast<long>(lnz) - n, res, status);
    cholmod_free_dense(&x, &c);
    cholmod_free_dense(&b, &c);
    cholmod_free_factor(&l, &c);
    cholmod_free_sparse(&a, &c);
    cholmod_free_triplet(&t, &c);
    cholmod_finish(&c);
}

// Eigen with ordering `Ordering` (AMD, or GivenOrdering on `given_perm`).
template <class Ordering>
static void eigen(const std::vector<Entry>& k, const std::vector<double>& rhs, int n, int reps,
                  const char* ordering) {
    std::vector<Eigen::Triplet<double>> triplets;
    for (const auto& e : k) triplets.emplace_back(e.row, e.col, e.value);
    Eigen::SparseMatrix<double> a(n, n);
    a.setFromTriplets(triplets.begin(), triplets.end());
    Eigen::Map<const Eigen::VectorXd> b(rhs.data(), n);
    using Ldlt = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Ordering>;
    Ldlt ldlt;
    double analysis = median_us(reps, [&] { ldlt.analyzePattern(a); });
    double factor = median_us(reps, [&] { ldlt.factorize(a); });
    std::string status = ldlt.info() == Eigen::Success ? "ok" : "zero pivot (NumericalIssue)";
    Eigen::VectorXd x(n);
    double solve = median_us(reps, [&] { x = ldlt.solve(b); });
    long nnz_l = ldlt.matrixL().nestedExpression().nonZeros();
    print("Eigen SimplicialLDLT", ordering, analysis, factor, solve, nnz_l,
          residual(k, rhs, x.data()), status);
}

int main(int argc, char** argv) {
    if (argc != 5) {
        std::fprintf(stderr, "usage: %s MATRIX.mtx RHS.mtx PERM REPS\n", argv[0]);
        return 2;
    }
    try {
        int n = 0;
        auto k = read_matrix(argv[1], n);
        auto b = read_rhs(argv[2], n);
        std::string name;
        given_perm = read_perm(argv[3], n, name);
        int reps = std::max(1, std::atoi(argv[4]));
        cholmod(k, b, n, reps, {}, name);
        cholmod(k, b, n, reps, given_perm, name);
        eigen<Eigen::AMDOrdering<int>>(k, b, n, reps, "AMD (Eigen)");
        eigen<GivenOrdering<int>>(k, b, n, reps, name.c_str());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "peers: %s\n", e.what());
        return 1;
    }
    return 0;
}
