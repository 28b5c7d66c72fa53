// Asks an installed libcam::dataset where a COLMAP model's images are: beside the model
// folder X/sparse/0, in X/images (COLMAP's own layout), as an absolute path.

#include <cstdio>

#include "libcam/dataset/colmap_dataset.hpp"

int main() {
    const std::filesystem::path images = libcam::default_dataset_images("/data/scene/sparse/0");
    std::printf("images %s\n", images.generic_string().c_str());
    return 0;
}
