#include "image_sources.hpp"

#include <algorithm>
#include <cmath>

#include "carbtf/analysis/image_io.hpp"
#include "carbtf/analysis/input_error.hpp"
#include "carbtf/analysis/progress.hpp"
#include "carbtf/reference/parallel_for.hpp"

namespace carbtf::detail {

std::string describe_direction(const Direction& d) {
  return "theta " + std::to_string(std::lround(d.theta_degrees())) + ", phi " +
         std::to_string(std::lround(d.phi_degrees()));
}

namespace {

void store(BtfDataset& dataset, const ImageSource& source, RgbImage&& image) {
  if (image.width != dataset.width() || image.height != dataset.height()) {
    throw InputError(source.name, "image is " + std::to_string(image.width) + "x" +
                                      std::to_string(image.height) + " but the others are " +
                                      std::to_string(dataset.width()) + "x" +
                                      std::to_string(dataset.height()));
  }
  const bool dataset_linear = dataset.encoding() == ColorEncoding::linear_half;
  if (image.linear != dataset_linear) {
    throw InputError(source.name, std::string("holds ") + (image.linear ? "linear float" : "8-bit sRGB") +
                                      " pixels but the others hold " +
                                      (dataset_linear ? "linear float" : "8-bit sRGB"));
  }
  if (image.linear) {
    dataset.set_linear(source.pair, image.linear_rgb);
  } else {
    dataset.set_srgb8(source.pair, std::move(image.srgb8));
  }
}

}  // namespace

BtfDataset decode_sources(const std::vector<ImageSource>& sources, std::vector<Direction> lights,
                          std::vector<Direction> views, std::string description,
                          const BtfLoadOptions& options, std::vector<std::string>& warnings,
                          const ImageAdjustment& adjust) {
  if (sources.empty()) throw InputError(description, "no images");
  check_direction_table(description, lights.size(), views.size(), sources.size());
  ImageShape shape;
  const ImageShape* expected = nullptr;  // none until the first image is decoded
  auto decode = [&](const ImageSource& source) {
    RgbImage image = decode_rgb_image(source.name, source.read(), expected);
    if (!expected) shape = {image.width, image.height, image.linear};  // as stored, before any adjustment
    if (adjust) adjust(source, image);
    return image;
  };
  // The first image fixes the size and encoding every other one must share.
  RgbImage first = decode(sources[0]);
  expected = &shape;
  BtfDataset dataset(std::move(lights), std::move(views), first.width, first.height,
                     first.linear ? ColorEncoding::linear_half : ColorEncoding::srgb8);
  dataset.source = std::move(description);
  dataset.chroma_halvings = first.chroma_halvings;
  store(dataset, sources[0], std::move(first));

  Progress progress("loading " + std::to_string(sources.size()) + " images", sources.size(),
                    options.progress);
  progress.advance();
  parallel_for(sources.size() - 1, options.threads, [&](std::size_t i) {
    store(dataset, sources[i + 1], decode(sources[i + 1]));
    progress.advance();
  });

  const std::vector<LightView> missing = dataset.missing_pairs();
  if (!missing.empty()) {
    std::string list;
    const std::size_t shown = std::min<std::size_t>(missing.size(), 8);
    for (std::size_t i = 0; i < shown; ++i) {
      list += (i ? "; " : "") + std::string("light ") +
              describe_direction(dataset.lights()[missing[i].light]) + " / view " +
              describe_direction(dataset.views()[missing[i].view]);
    }
    if (missing.size() > shown) list += "; and " + std::to_string(missing.size() - shown) + " more";
    warnings.push_back(dataset.source + ": partial dataset, " + std::to_string(missing.size()) + " of " +
                       std::to_string(dataset.lights().size() * dataset.views().size()) +
                       " light/view pairs missing: " + list);
  }
  return dataset;
}

}  // namespace carbtf::detail
