#include "libcam/fit/error_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "libcam/error.hpp"
#include "libcam/geometry/pixel_grid.hpp"

namespace libcam {

FitErrorMap fit_error_map(const Camera& source, const FittedModel& fitted, const std::vector<double>& depths,
                          long columns, long rows) {
    if (columns < 1 || rows < 1) {
        throw InvalidArgument("error map: needs at least 1x1 tiles, got " + std::to_string(columns) + "x" +
                              std::to_string(rows));
    }
    FitErrorMap map{source.size, columns, rows, {}};
    const std::vector<Vec2> pixels = tile_centres(source.size, columns, rows);
    map.error_px.assign(pixels.size(), std::numeric_limits<double>::quiet_NaN());

    // The tiles the source has a ray through, with that ray.
    const std::vector<Unprojection> rays = PreparedCamera(source).unproject(pixels);
    ScenePixels with_ray;
    std::vector<std::size_t> tile_of;
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        if (!rays[i].valid) continue;
        with_ray.pixels.push_back(pixels[i]);
        with_ray.directions.push_back(rays[i].direction.normalized());
        tile_of.push_back(i);
    }
    if (tile_of.empty()) return map;

    // observations_of lists every pixel at the first depth, then at the next, ...
    const std::vector<double> errors = reprojection_errors(fitted.camera, observations_of(with_ray, depths));
    for (std::size_t k = 0; k < errors.size(); ++k) {
        double& worst = map.error_px[tile_of[k % tile_of.size()]];
        worst = std::isnan(worst) ? errors[k] : std::max(worst, errors[k]);
    }
    return map;
}

}  // namespace libcam
