#include "libcam/fit/least_squares.hpp"

#include <ceres/ceres.h>
#include <ceres/rotation.h>
#include <glog/logging.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <utility>

#include "libcam/error.hpp"
#include "libcam/fit/observation_fit.hpp"
#include "libcam/lens/lens_models.hpp"

namespace libcam::detail {

namespace {

double scalar_part(double value) { return value; }
template <int N>
double scalar_part(const ceres::Jet<double, N>& value) {
    return value.a;
}

// The lens parameters of Model in the solver's scalar T, from its free coefficients
// after kHeld leading ones held at 0. The valid radius (where the distortion folds over)
// is worked out from the coefficients' values and held fixed while differentiating: it
// bounds the domain, it is not part of any residual.
template <class Model, int kHeld, class T>
typename LensInScalar<Model, T>::Parameters lens_parameters(const T* free_coefficients) {
    constexpr int kCount = Model::num_coefficients;
    std::array<double, kCount> values{};
    typename LensInScalar<Model, T>::Parameters lens;
    for (int i = 0; i < kCount; ++i) {
        const T value = i < kHeld ? T(0) : free_coefficients[i - kHeld];
        values[static_cast<std::size_t>(i)] = scalar_part(value);
        lens.coefficients(i) = value;
    }
    lens.valid_radius = T(static_cast<double>(Model::parameters(values).valid_radius));
    return lens;
}

// How K's free parameters sit at the start of a candidate's parameters.
enum class Core {
    Focal,           // the look-at camera: f, the principal point at the image centre
    PrincipalPoint,  // cx cy, square pixels at a sensor's fixed scale
    Full,            // fx fy cx cy
};

// What the fit holds fixed: the look-at camera's principal point, a sensor's scale.
struct HeldIntrinsics {
    Vec2 image_centre = Vec2::Zero();
    double focal = 0.0;
};

// K without skew (geometry/intrinsics.hpp), in the solver's scalar.
template <Core kCore, class T>
Eigen::Matrix<T, 2, 1> pixel_from_normalized(const T* core, const HeldIntrinsics& held, const Eigen::Matrix<T, 2, 1>& m) {
    if constexpr (kCore == Core::Focal) {
        return {core[0] * m.x() + T(held.image_centre.x()), core[0] * m.y() + T(held.image_centre.y())};
    } else if constexpr (kCore == Core::PrincipalPoint) {
        return {T(held.focal) * m.x() + core[0], T(held.focal) * m.y() + core[1]};
    } else {
        return {core[0] * m.x() + core[2], core[1] * m.y() + core[3]};
    }
}

// Are these coefficients the model's (DOUBLE_SPHERE's alpha in [0, 1], ...)? A step
// that leaves them is rejected.
template <class Model, std::size_t N>
bool coefficients_allowed(const std::array<double, N>& values) {
    try {
        Lens{Model::type, std::vector<double>(values.begin(), values.end())}.validate("fit");
        return true;
    } catch (const InvalidArgument&) {
        return false;
    }
}

// Every observation's reprojection error at once (one residual block), so that the
// lens's valid radius is worked out once per evaluation, not once per observation.
template <class Model, Core kCore>
class ReprojectionResiduals {
public:
    static constexpr int kCoreParams = kCore == Core::Focal ? 1 : kCore == Core::PrincipalPoint ? 2 : 4;
    static constexpr int kHeld = lens_info(Model::type).fit_held_coefficients;
    static constexpr int kParams = kCoreParams + Model::num_coefficients - kHeld;

    ReprojectionResiduals(const std::vector<FitSample>& observations, const std::vector<FitSample>& must_project,
                          const HeldIntrinsics& held)
        : observations_(observations), must_project_(must_project), held_(held) {}

    // False when the coefficients leave the model's range or a point leaves its valid
    // domain: Ceres then rejects the step.
    template <class T>
    bool operator()(const T* intrinsics, const T* rotation, const T* shift, T* residuals) const {
        if (!acceptable(intrinsics, rotation, shift)) return false;
        const typename LensInScalar<Model, T>::Parameters lens = lens_parameters<Model, kHeld>(intrinsics + kCoreParams);
        for (std::size_t i = 0; i < observations_.size(); ++i) {
            Eigen::Matrix<T, 2, 1> m;
            if (!project(lens, observations_[i].point, rotation, shift, m)) return false;
            const Eigen::Matrix<T, 2, 1> pixel = pixel_from_normalized<kCore>(intrinsics, held_, m);
            residuals[2 * i] = pixel.x() - T(observations_[i].pixel.x());
            residuals[2 * i + 1] = pixel.y() - T(observations_[i].pixel.y());
        }
        return true;
    }

private:
    // m of a source-frame point, after the camera's motion.
    template <class T>
    static bool project(const typename LensInScalar<Model, T>::Parameters& lens, const Vec3& source_point,
                        const T* rotation, const T* shift, Eigen::Matrix<T, 2, 1>& m) {
        const T point[3] = {T(source_point.x()), T(source_point.y()), T(source_point.z())};
        T turned[3];
        ceres::AngleAxisRotatePoint(rotation, point, turned);
        const Eigen::Matrix<T, 3, 1> camera_point(turned[0] + shift[0], turned[1] + shift[1], turned[2] + shift[2]);
        return LensInScalar<Model, T>::project(lens, camera_point, m);
    }

    // Are the coefficients in the model's range, and do the must_project points project?
    // Only validity matters here, so in double.
    template <class T>
    bool acceptable(const T* intrinsics, const T* rotation, const T* shift) const {
        std::array<double, kParams> values{};
        for (int i = 0; i < kParams; ++i) values[static_cast<std::size_t>(i)] = scalar_part(intrinsics[i]);
        std::array<double, Model::num_coefficients> coefficients{};
        for (int i = kHeld; i < Model::num_coefficients; ++i) {
            coefficients[static_cast<std::size_t>(i)] = values[static_cast<std::size_t>(kCoreParams + i - kHeld)];
        }
        if (!coefficients_allowed<Model>(coefficients)) return false;
        if (must_project_.empty()) return true;
        const double turn[3] = {scalar_part(rotation[0]), scalar_part(rotation[1]), scalar_part(rotation[2])};
        const double move[3] = {scalar_part(shift[0]), scalar_part(shift[1]), scalar_part(shift[2])};
        const typename Model::Parameters lens = lens_parameters<Model, kHeld>(values.data() + kCoreParams);
        Vec2 m;
        for (const FitSample& guard : must_project_) {
            if (!project<double>(lens, guard.point, turn, move, m)) return false;
        }
        return true;
    }

    const std::vector<FitSample>& observations_;
    const std::vector<FitSample>& must_project_;
    HeldIntrinsics held_;
};

// The second camera of a pair: a board point carried into the first camera by the board's
// pose, into the second by the pair's, then projected (solve_pair).
template <class Model, Core kCore>
class SecondCameraResiduals {
public:
    static constexpr int kCoreParams = ReprojectionResiduals<Model, kCore>::kCoreParams;
    static constexpr int kHeld = ReprojectionResiduals<Model, kCore>::kHeld;
    static constexpr int kParams = ReprojectionResiduals<Model, kCore>::kParams;

    SecondCameraResiduals(const std::vector<FitSample>& observations, const HeldIntrinsics& held)
        : observations_(observations), held_(held) {}

    template <class T>
    bool operator()(const T* intrinsics, const T* board_rotation, const T* board_shift, const T* rotation,
                    const T* shift, T* residuals) const {
        std::array<double, Model::num_coefficients> coefficients{};
        for (int i = kHeld; i < Model::num_coefficients; ++i) {
            coefficients[static_cast<std::size_t>(i)] = scalar_part(intrinsics[kCoreParams + i - kHeld]);
        }
        if (!coefficients_allowed<Model>(coefficients)) return false;
        const typename LensInScalar<Model, T>::Parameters lens = lens_parameters<Model, kHeld>(intrinsics + kCoreParams);
        for (std::size_t i = 0; i < observations_.size(); ++i) {
            const Vec3& p = observations_[i].point;
            const T point[3] = {T(p.x()), T(p.y()), T(p.z())};
            T on_board[3], in_second[3];
            ceres::AngleAxisRotatePoint(board_rotation, point, on_board);
            for (int k = 0; k < 3; ++k) on_board[k] += board_shift[k];
            ceres::AngleAxisRotatePoint(rotation, on_board, in_second);
            const Eigen::Matrix<T, 3, 1> camera_point(in_second[0] + shift[0], in_second[1] + shift[1],
                                                      in_second[2] + shift[2]);
            Eigen::Matrix<T, 2, 1> m;
            if (!LensInScalar<Model, T>::project(lens, camera_point, m)) return false;
            const Eigen::Matrix<T, 2, 1> pixel = pixel_from_normalized<kCore>(intrinsics, held_, m);
            residuals[2 * i] = pixel.x() - T(observations_[i].pixel.x());
            residuals[2 * i + 1] = pixel.y() - T(observations_[i].pixel.y());
        }
        return true;
    }

private:
    const std::vector<FitSample>& observations_;
    HeldIntrinsics held_;
};

// Reports each iteration, and ends the solve once the RMS error is negligible.
class IterationWatch : public ceres::IterationCallback {
public:
    IterationWatch(const IterationHook& hook, std::size_t observations, double negligible_rms_px)
        : hook_(hook), observations_(static_cast<double>(observations)), negligible_rms_px_(negligible_rms_px) {}

    ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
        if (hook_) hook_(summary.iteration);
        // Ceres's cost is half the sum of squared residuals: sum |error|^2 = 2 cost.
        const double rms_px = std::sqrt(2.0 * summary.cost / observations_);
        return rms_px < negligible_rms_px_ ? ceres::SOLVER_TERMINATE_SUCCESSFULLY : ceres::SOLVER_CONTINUE;
    }

private:
    const IterationHook& hook_;
    double observations_;
    double negligible_rms_px_;
};

// Ceres reports a rejected step or a singular system through glog, to stderr when the
// program has not set glog up: lines a user of libcam fit cannot act on (the solver
// recovers, and a failed candidate is reported as such). Quiet unless the program set up
// glog itself, once per process.
void quiet_solver_log() {
    static const bool quieted = [] {
        if (!google::IsGoogleLoggingInitialized()) FLAGS_minloglevel = google::GLOG_FATAL;
        return true;
    }();
    (void)quieted;
}

// Levenberg-Marquardt, converged to rounding: the fit's error is what `libcam fit`
// reports, and it has to be the model's best, not the solver's first acceptable one.
ceres::Solver::Options solver_options() {
    quiet_solver_log();
    ceres::Solver::Options options;
    options.minimizer_type = ceres::TRUST_REGION;
    options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
    options.linear_solver_type = ceres::DENSE_QR;
    options.max_num_iterations = 500;
    options.function_tolerance = 1e-15;
    options.gradient_tolerance = 1e-15;
    options.parameter_tolerance = 1e-15;
    options.num_threads = 1;
    options.logging_type = ceres::SILENT;
    return options;
}

// Runs the solver; throws InvalidArgument naming the model where it fails outright.
// Returns the iterations it took.
int solve_or_throw(const ceres::Solver::Options& options, ceres::Problem& problem, LensType model) {
    ceres::Solver::Summary summary;
    ceres::Solve(options, &problem, &summary);
    if (summary.termination_type == ceres::FAILURE) {
        throw InvalidArgument("fit: the solver failed for " + std::string(lens_info(model).name) + ": " +
                              summary.message);
    }
    return static_cast<int>(summary.iterations.size());
}

// The intrinsics move only along the candidate's free directions B (free_directions,
// orthonormal columns): x + B delta, so that what is held stays held.
class FreeDirectionsManifold : public ceres::Manifold {
public:
    explicit FreeDirectionsManifold(Eigen::MatrixXd directions) : directions_(std::move(directions)) {}
    int AmbientSize() const override { return static_cast<int>(directions_.rows()); }
    int TangentSize() const override { return static_cast<int>(directions_.cols()); }
    bool Plus(const double* x, const double* delta, double* x_plus_delta) const override {
        Eigen::Map<Eigen::VectorXd>(x_plus_delta, directions_.rows()) =
            Eigen::Map<const Eigen::VectorXd>(x, directions_.rows()) +
            directions_ * Eigen::Map<const Eigen::VectorXd>(delta, directions_.cols());
        return true;
    }
    bool PlusJacobian(const double* /*x*/, double* jacobian) const override {
        Eigen::Map<RowMajor>(jacobian, directions_.rows(), directions_.cols()) = directions_;
        return true;
    }
    bool Minus(const double* y, const double* x, double* y_minus_x) const override {
        Eigen::Map<Eigen::VectorXd>(y_minus_x, directions_.cols()) =
            directions_.transpose() * (Eigen::Map<const Eigen::VectorXd>(y, directions_.rows()) -
                                       Eigen::Map<const Eigen::VectorXd>(x, directions_.rows()));
        return true;
    }
    bool MinusJacobian(const double* /*x*/, double* jacobian) const override {
        Eigen::Map<RowMajor>(jacobian, directions_.cols(), directions_.rows()) = directions_.transpose();
        return true;
    }

private:
    using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    Eigen::MatrixXd directions_;
};

// The candidate's held parameters: the start moved onto them (B B^T params) and the solver
// kept on them. Nothing held: nothing done.
void hold_parameters(const Candidate& candidate, ceres::Problem& problem, std::vector<double>& params) {
    if (!candidate.held.any()) return;
    Eigen::MatrixXd directions = free_directions(candidate);
    Eigen::Map<Eigen::VectorXd> values(params.data(), static_cast<Eigen::Index>(params.size()));
    values = directions * (directions.transpose() * values);
    problem.SetManifold(params.data(), new FreeDirectionsManifold(std::move(directions)));
}

template <class Model, Core kCore>
LeastSquaresState solve_with(const Candidate& candidate, const HeldIntrinsics& held, const std::vector<FitSample>& observations,
                             LeastSquaresState state, const SolveOptions& settings, const IterationHook& hook) {
    using Residuals = ReprojectionResiduals<Model, kCore>;
    if (state.params.size() != static_cast<std::size_t>(Residuals::kParams)) {
        throw InvalidArgument("fit: a start with " + std::to_string(state.params.size()) + " parameters for a model with " +
                              std::to_string(Residuals::kParams));
    }
    auto* cost = new ceres::AutoDiffCostFunction<Residuals, ceres::DYNAMIC, Residuals::kParams, 3, 3>(
        new Residuals(observations, settings.must_project, held), static_cast<int>(2 * observations.size()));
    ceres::Problem problem;
    problem.AddResidualBlock(cost, nullptr, state.params.data(), state.rotation.data(), state.shift.data());
    hold_parameters(candidate, problem, state.params);
    if (settings.motion == CameraMotion::None) problem.SetParameterBlockConstant(state.rotation.data());
    if (settings.motion != CameraMotion::RotationAndShift) problem.SetParameterBlockConstant(state.shift.data());

    ceres::Solver::Options options = solver_options();
    IterationWatch watch(hook, observations.size(), settings.negligible_rms_px);
    options.callbacks.push_back(&watch);
    state.iterations = solve_or_throw(options, problem, Model::type);
    return state;
}

template <class Model, Core kCore>
ViewsState solve_views_with(const Candidate& candidate, const HeldIntrinsics& held, const std::vector<std::vector<FitSample>>& views,
                            ViewsState state, bool hold_intrinsics) {
    using Residuals = ReprojectionResiduals<Model, kCore>;
    if (state.params.size() != static_cast<std::size_t>(Residuals::kParams) || state.rotations.size() != views.size() ||
        state.shifts.size() != views.size()) {
        throw InvalidArgument("fit: a start that does not match the model and the views");
    }
    static const std::vector<FitSample> kNoGuards;
    ceres::Problem problem;
    std::size_t observations = 0;
    for (std::size_t v = 0; v < views.size(); ++v) {
        if (views[v].empty()) continue;
        auto* cost = new ceres::AutoDiffCostFunction<Residuals, ceres::DYNAMIC, Residuals::kParams, 3, 3>(
            new Residuals(views[v], kNoGuards, held), static_cast<int>(2 * views[v].size()));
        problem.AddResidualBlock(cost, nullptr, state.params.data(), state.rotations[v].data(), state.shifts[v].data());
        observations += views[v].size();
    }
    if (observations == 0) throw InvalidArgument("fit: no observations to fit");
    if (hold_intrinsics) {
        problem.SetParameterBlockConstant(state.params.data());
    } else {
        hold_parameters(candidate, problem, state.params);
    }
    ceres::Solver::Options options = solver_options();
    // The poses are independent given the intrinsics: Ceres eliminates them (the Schur
    // complement), leaving a system the size of the intrinsics.
    if (views.size() > 1 && !hold_intrinsics) options.linear_solver_type = ceres::DENSE_SCHUR;
    options.max_num_iterations = 200;
    options.function_tolerance = 1e-12;
    options.parameter_tolerance = 1e-12;
    state.iterations = solve_or_throw(options, problem, Model::type);
    return state;
}

// Calls body.template operator()<Model, kCore>() for the candidate's model and K.
template <class Body>
auto with_candidate(const Candidate& candidate, Body&& body) {
    using Result = decltype(body.template operator()<PinholeLens<double>, Core::Focal>());
    if (candidate.look_at) return body.template operator()<PinholeLens<double>, Core::Focal>();
    return visit_lens_model<double>(candidate.lens, [&]<class Model>() -> Result {
        // Only the table's candidates are compiled for the solver (each is a Ceres
        // instantiation of its own).
        constexpr LensInfo info = lens_info(Model::type);
        if constexpr (info.fit != FitCandidate::No) {
            constexpr Core kCore = info.fit_sensor_width_mm > 0.0 ? Core::PrincipalPoint : Core::Full;
            return body.template operator()<Model, kCore>();
        } else {
            throw InvalidArgument("fit: " + std::string(info.name) + " is not a fit candidate");
        }
    });
}

// The first camera's residual blocks of a pair (solve_pair): as solve_views_with's.
template <class Model, Core kCore>
void add_first_camera(const Candidate& candidate, const HeldIntrinsics& held, const std::vector<std::vector<FitSample>>& views,
                      ViewsState& state, ceres::Problem& problem) {
    using Residuals = ReprojectionResiduals<Model, kCore>;
    if (state.params.size() != static_cast<std::size_t>(Residuals::kParams)) {
        throw InvalidArgument("fit: a start that does not match the first camera's model");
    }
    static const std::vector<FitSample> kNoGuards;
    for (std::size_t v = 0; v < views.size(); ++v) {
        if (views[v].empty()) continue;
        auto* cost = new ceres::AutoDiffCostFunction<Residuals, ceres::DYNAMIC, Residuals::kParams, 3, 3>(
            new Residuals(views[v], kNoGuards, held), static_cast<int>(2 * views[v].size()));
        problem.AddResidualBlock(cost, nullptr, state.params.data(), state.rotations[v].data(), state.shifts[v].data());
    }
    hold_parameters(candidate, problem, state.params);
}

// The second camera's residual blocks of a pair, through the pair's pose.
template <class Model, Core kCore>
void add_second_camera(const Candidate& candidate, const HeldIntrinsics& held,
                       const std::vector<std::vector<FitSample>>& views, PairState& state, ceres::Problem& problem) {
    using Residuals = SecondCameraResiduals<Model, kCore>;
    if (state.second.size() != static_cast<std::size_t>(Residuals::kParams)) {
        throw InvalidArgument("fit: a start that does not match the second camera's model");
    }
    for (std::size_t v = 0; v < views.size(); ++v) {
        if (views[v].empty()) continue;
        auto* cost = new ceres::AutoDiffCostFunction<Residuals, ceres::DYNAMIC, Residuals::kParams, 3, 3, 3, 3>(
            new Residuals(views[v], held), static_cast<int>(2 * views[v].size()));
        problem.AddResidualBlock(cost, nullptr, state.second.data(), state.first.rotations[v].data(),
                                 state.first.shifts[v].data(), state.rotation.data(), state.shift.data());
    }
    hold_parameters(candidate, problem, state.second);
}

HeldIntrinsics held_for(const Candidate& candidate, const ImageSize& size) {
    HeldIntrinsics held;
    held.image_centre = {size.centre_x(), size.centre_y()};
    if (candidate.sensor_width_mm > 0.0) held.focal = candidate.sensor_pixels_per_mm(size.width);
    return held;
}

// The residuals of one set of observations under `params` and a pose, and their
// derivatives, by the solver's own residual and automatic differentiation.
template <class Model, Core kCore>
ResidualDerivatives derivatives_with(const HeldIntrinsics& held, const std::vector<double>& params, const Vec3& rotation,
                                     const Vec3& shift, const std::vector<FitSample>& observations) {
    using Residuals = ReprojectionResiduals<Model, kCore>;
    if (params.size() != static_cast<std::size_t>(Residuals::kParams)) {
        throw InvalidArgument("fit: " + std::to_string(params.size()) + " parameters for a model with " +
                              std::to_string(Residuals::kParams));
    }
    static const std::vector<FitSample> kNoGuards;
    const auto rows = static_cast<Eigen::Index>(2 * observations.size());
    ResidualDerivatives out;
    if (observations.empty()) {
        out.by_intrinsics.resize(0, Residuals::kParams);
        out.by_pose.resize(0, 6);
        return out;
    }
    ceres::AutoDiffCostFunction<Residuals, ceres::DYNAMIC, Residuals::kParams, 3, 3> cost(
        new Residuals(observations, kNoGuards, held), static_cast<int>(rows));
    // Ceres writes each block's Jacobian row-major.
    using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    RowMajor by_intrinsics(rows, Residuals::kParams), by_rotation(rows, 3), by_shift(rows, 3);
    out.residuals.resize(rows);
    const double* blocks[3] = {params.data(), rotation.data(), shift.data()};
    double* jacobians[3] = {by_intrinsics.data(), by_rotation.data(), by_shift.data()};
    if (!cost.Evaluate(blocks, out.residuals.data(), jacobians)) {
        throw InvalidArgument("fit: an observation lies outside the " + std::string(lens_info(Model::type).name) +
                              " model's valid domain, or its coefficients are out of the model's range");
    }
    out.by_intrinsics = by_intrinsics;
    out.by_pose.resize(rows, 6);
    out.by_pose << by_rotation, by_shift;
    return out;
}

}  // namespace

ViewsState solve_views(const Candidate& candidate, const ImageSize& size,
                       const std::vector<std::vector<FitSample>>& views, ViewsState start, bool hold_intrinsics) {
    const HeldIntrinsics held = held_for(candidate, size);
    return with_candidate(candidate, [&]<class Model, Core kCore>() {
        return solve_views_with<Model, kCore>(candidate, held, views, std::move(start), hold_intrinsics);
    });
}

PairState solve_pair(const Candidate& first, const ImageSize& first_size, const Candidate& second,
                     const ImageSize& second_size, const std::vector<std::vector<FitSample>>& first_views,
                     const std::vector<std::vector<FitSample>>& second_views, PairState state) {
    const std::size_t views = first_views.size();
    if (second_views.size() != views || state.first.rotations.size() != views || state.first.shifts.size() != views) {
        throw InvalidArgument("fit: a pair's start that does not match its views");
    }
    ceres::Problem problem;
    const HeldIntrinsics first_held = held_for(first, first_size), second_held = held_for(second, second_size);
    with_candidate(first, [&]<class Model, Core kCore>() {
        add_first_camera<Model, kCore>(first, first_held, first_views, state.first, problem);
    });
    with_candidate(second, [&]<class Model, Core kCore>() {
        add_second_camera<Model, kCore>(second, second_held, second_views, state, problem);
    });
    if (problem.NumResidualBlocks() == 0) throw InvalidArgument("fit: no observations to fit");
    ceres::Solver::Options options = solver_options();
    // The board poses are independent given the intrinsics and the pair's pose: eliminated.
    options.linear_solver_type = ceres::DENSE_SCHUR;
    options.max_num_iterations = 200;
    options.function_tolerance = 1e-12;
    options.parameter_tolerance = 1e-12;
    state.first.iterations = solve_or_throw(options, problem, second.lens);
    return state;
}

LeastSquaresState solve_least_squares(const Candidate& candidate, const ImageSize& size,
                                      const std::vector<FitSample>& observations, LeastSquaresState start,
                                      const SolveOptions& options, const IterationHook& hook) {
    const HeldIntrinsics held = held_for(candidate, size);
    return with_candidate(candidate, [&]<class Model, Core kCore>() {
        return solve_with<Model, kCore>(candidate, held, observations, std::move(start), options, hook);
    });
}

}  // namespace libcam::detail

namespace libcam {

ResidualDerivatives residual_derivatives(const Candidate& candidate, const ImageSize& size,
                                         const std::vector<double>& params, const Pose& pose,
                                         const std::vector<FitSample>& observations) {
    const detail::HeldIntrinsics held = detail::held_for(candidate, size);
    const Vec3 rotation = pose.rvec();
    return detail::with_candidate(candidate, [&]<class Model, detail::Core kCore>() {
        return detail::derivatives_with<Model, kCore>(held, params, rotation, pose.t, observations);
    });
}

}  // namespace libcam
