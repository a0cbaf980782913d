// The Bonn UBO2014 `.btf` reader (analysis/btf/ubo2014_format.hpp holds the layout). DFMF files keep
// their factors in memory and rebuild an image when it is asked for; raw (BDI) files are read chunk by
// chunk into half-float images. Every declared size is checked against the file's length and carbtf's
// limits before anything is allocated for it.
#include <unistd.h>

#include <Imath/half.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "bounded_file.hpp"
#include "carbtf/analysis/btf/btf_reader.hpp"
#include "carbtf/analysis/btf/ubo2014_format.hpp"
#include "carbtf/analysis/progress.hpp"
#include "image_sources.hpp"
#include "ubo2014_colour.hpp"

namespace carbtf {

namespace {

using detail::BoundedFile;

struct Header {
  ubo2014::Layout layout = ubo2014::Layout::dfmf;
  bool cosine_in_data = false;
  std::vector<Direction> lights;
  std::vector<Direction> views;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::size_t pairs() const { return lights.size() * views.size(); }
  std::size_t texels() const { return std::size_t{width} * height; }
};

std::string mib(std::uint64_t bytes) {
  return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB";
}

std::uint64_t physical_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long page_size = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page_size > 0
             ? static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page_size)
             : 0;
}

void require_memory(const BoundedFile& file, std::uint64_t bytes, const std::string& what) {
  const std::uint64_t available = physical_memory_bytes();
  if (available != 0 && bytes > available / 10 * 8) {
    file.fail(what, "needs " + mib(bytes) + " of memory, more than 80% of this machine's " + mib(available));
  }
}

ubo2014::Layout read_signature(BoundedFile& file) {
  std::array<char, 10> bytes{};
  file.read(bytes.data(), std::min<std::uint64_t>(bytes.size(), file.size()), "signature");
  const std::string_view signature(bytes.data(), bytes.size());
  if (signature == ubo2014::kDfmfSignature) return ubo2014::Layout::dfmf;
  if (signature == ubo2014::kBdiSignature) return ubo2014::Layout::bdi;
  for (const char* other : {"!FMF", "!PVF", "!BDI"}) {
    if (signature.starts_with(other)) {
      file.fail("signature", "a UBO BTF in a layout carbtf does not read (" + std::string(other + 1) +
                                 "); carbtf reads \"" + std::string(ubo2014::kDfmfSignature) +
                                 "\" (DFMF) and \"" + std::string(ubo2014::kBdiSignature) + "\" (raw)");
    }
  }
  file.fail("signature", "not a UBO2014 BTF file (it starts neither with \"" +
                             std::string(ubo2014::kDfmfSignature) + "\" nor \"" +
                             std::string(ubo2014::kBdiSignature) + "\")");
}

void read_meta_data(BoundedFile& file, Header& header) {
  const std::uint64_t start = file.position();
  const auto block_size = file.value<std::uint32_t>("meta data size");
  const auto version = file.value<std::uint32_t>("meta data version");
  if (version < 1 || version > 4)
    file.fail("meta data version", std::to_string(version) + " is not one of 1-4");
  file.skip(3 * 80 + 4 + 3 * 4, "meta data (setup, sensor, light source, scale)");
  header.cosine_in_data = version > 1 && file.value<std::uint32_t>("meta data cosine flag") != 0;
  if (version > 2) file.skip(file.value<std::uint32_t>("meta data XML size"), "meta data XML");
  std::uint32_t channels = 3;
  if (version > 3) {
    channels = file.value<std::uint32_t>("meta data channel count");
    if (channels > ubo2014::kMaxChannels)
      file.fail("meta data channel count",
                std::to_string(channels) + " is over the limit of " + std::to_string(ubo2014::kMaxChannels));
    for (std::uint32_t c = 0; c < channels; ++c) {
      file.skip(file.value<std::uint32_t>("meta data channel name size"),
                "meta data channel " + std::to_string(c) + " name");
    }
  }
  if (channels != 3)
    file.fail("meta data channel count", std::to_string(channels) + " channels; carbtf reads RGB BTFs (3)");
  if (file.position() - start != block_size) {
    file.fail("meta data size", "declares " + std::to_string(block_size) + " bytes but its fields take " +
                                    std::to_string(file.position() - start));
  }
}

Direction read_direction(BoundedFile& file, const std::string& field) {
  const auto theta = file.value<float>(field + " theta");
  const auto phi = file.value<float>(field + " phi");
  if (!std::isfinite(theta) || !std::isfinite(phi)) file.fail(field, "angle is not a finite number");
  if (theta < 0 || theta >= std::numbers::pi_v<float> / 2) {
    file.fail(field,
              "theta " + std::to_string(theta) + " rad is not in [0, pi/2): not a direction over the sample");
  }
  return {theta, std::fmod(std::fmod(static_cast<double>(phi), 2 * std::numbers::pi) + 2 * std::numbers::pi,
                           2 * std::numbers::pi)};
}

void read_directions(BoundedFile& file, Header& header, std::vector<std::string>& warnings) {
  const auto views = file.value<std::uint32_t>("view count");
  if (views == 0) file.fail("view count", "0 views");
  check_direction_table(file.path().string(), 1, views, 1);
  file.require(std::uint64_t{views} * 12, "view table");
  header.views.reserve(views);
  bool lights_differ = false;
  for (std::uint32_t v = 0; v < views; ++v) {
    header.views.push_back(read_direction(file, "view " + std::to_string(v)));
    const auto lights = file.value<std::uint32_t>("view " + std::to_string(v) + " light count");
    if (v == 0) {
      if (lights == 0) file.fail("view 0 light count", "0 lights");
      check_direction_table(file.path().string(), lights, views, std::uint64_t{lights} * views);
      file.require(std::uint64_t{lights} * 8, "view 0 light table");
      header.lights.reserve(lights);
    } else if (lights != header.lights.size()) {
      file.fail("view " + std::to_string(v) + " light count",
                std::to_string(lights) + " lights where view 0 has " + std::to_string(header.lights.size()) +
                    "; carbtf reads files whose views share one light set");
    }
    for (std::uint32_t l = 0; l < lights; ++l) {
      const Direction d = read_direction(file, "view " + std::to_string(v) + " light " + std::to_string(l));
      if (v == 0) {
        header.lights.push_back(d);
      } else if (angle_between(d, header.lights[l]) > 1e-4) {
        lights_differ = true;
      }
    }
  }
  if (lights_differ) {
    warnings.push_back(file.path().string() +
                       ": the views list different light directions; carbtf uses view 0's, as btflib does");
  }
}

void read_extent(BoundedFile& file, Header& header) {
  header.width = file.value<std::uint32_t>("width");
  header.height = file.value<std::uint32_t>("height");
  for (const auto& [side, name] : {std::pair{header.width, "width"}, std::pair{header.height, "height"}}) {
    if (side == 0 || side > ubo2014::kMaxSide)
      file.fail(name, std::to_string(side) + " texels is not in 1-" + std::to_string(ubo2014::kMaxSide));
  }
}

void skip_rotations(BoundedFile& file) {
  const auto rotations = file.value<std::uint32_t>("rotation count");
  if (rotations > ubo2014::kMaxRotations)
    file.fail("rotation count",
              std::to_string(rotations) + " is over the limit of " + std::to_string(ubo2014::kMaxRotations));
  file.skip(std::uint64_t{rotations} * 9 * 4, "rotations");
}

bool half_is_finite(std::uint16_t bits) {
  return (bits & 0x7c00u) != 0x7c00u;
}

// Per light, the factor that makes the file's values photographs: 1 where the cosine is in the data.
std::vector<float> light_cosines(const Header& header) {
  std::vector<float> cosines(header.lights.size(), 1.0f);
  if (!header.cosine_in_data) {
    for (std::size_t l = 0; l < cosines.size(); ++l)
      cosines[l] = static_cast<float>(std::cos(header.lights[l].theta));
  }
  return cosines;
}

// ---- DFMF ----

// One channel's factors as float: a row per texel and a row per light/view pair (light fastest).
struct ChannelFactors {
  std::uint32_t components = 0;
  std::vector<float> texel_rows;
  std::vector<float> pair_rows;
};

void read_scalars(BoundedFile& file, std::uint8_t scalar_bytes, std::uint64_t count, float* out,
                  const std::string& field) {
  constexpr std::uint64_t kBlock = 1u << 16;
  std::vector<std::uint8_t> block(std::min(count, kBlock) * scalar_bytes);
  for (std::uint64_t done = 0; done < count;) {
    const std::uint64_t n = std::min(count - done, kBlock);
    file.read(block.data(), n * scalar_bytes, field);
    for (std::uint64_t i = 0; i < n; ++i) {
      double value = 0;
      if (scalar_bytes == 2) {
        std::uint16_t bits;
        std::memcpy(&bits, &block[i * 2], 2);
        Imath::half h;
        h.setBits(bits);
        value = static_cast<float>(h);
      } else if (scalar_bytes == 4) {
        float f;
        std::memcpy(&f, &block[i * 4], 4);
        value = f;
      } else {
        std::memcpy(&value, &block[i * 8], 8);
      }
      if (!std::isfinite(value) || std::abs(value) > 3e38) {
        file.fail(field, "value " + std::to_string(done + i) + " is not a finite float");
      }
      out[done + i] = static_cast<float>(value);
    }
    done += n;
  }
}

ChannelFactors read_channel(BoundedFile& file, const Header& header, std::uint32_t channel,
                            std::uint32_t max_components) {
  const std::string name = "DFMF channel " + std::to_string(channel);
  const auto scalar_bytes = file.value<std::uint8_t>(name + " scalar size");
  if (scalar_bytes != 2 && scalar_bytes != 4 && scalar_bytes != 8) {
    file.fail(name + " scalar size",
              std::to_string(scalar_bytes) + " bytes is none of 2 (half), 4 (float), 8 (double)");
  }
  const auto components = file.value<std::uint32_t>(name + " component count");
  const auto rows = file.value<std::uint32_t>(name + " row count");
  const auto columns = file.value<std::uint32_t>(name + " column count");
  const bool pairs_in_rows = rows == header.pairs() && columns == header.texels();
  if (!pairs_in_rows && !(rows == header.texels() && columns == header.pairs())) {
    file.fail(name + " rows and columns", std::to_string(rows) + " x " + std::to_string(columns) +
                                              " do not match the tables: " + std::to_string(header.pairs()) +
                                              " light/view pairs and " + std::to_string(header.texels()) +
                                              " texels");
  }
  if (components == 0 || components > max_components) {
    file.fail(name + " component count", std::to_string(components) + " is not in 1-" +
                                             std::to_string(max_components) + " (the header's count)");
  }
  if (components > std::min(rows, columns)) {
    file.fail(name + " component count", std::to_string(components) + " components of a " +
                                             std::to_string(rows) + " x " + std::to_string(columns) +
                                             " matrix");
  }
  const std::uint64_t values = std::uint64_t{components} * (1 + std::uint64_t{rows} + columns);
  file.require(values * scalar_bytes, name + " factors");
  require_memory(file, values * sizeof(float) * 3, name + " factors");
  ChannelFactors factors;
  factors.components = components;
  std::vector<float> singular(components);
  read_scalars(file, scalar_bytes, components, singular.data(), name + " singular values");
  std::vector<float> u(std::uint64_t{rows} * components);
  read_scalars(file, scalar_bytes, u.size(), u.data(), name + " U");
  std::vector<float> sv(std::uint64_t{columns} * components);
  read_scalars(file, scalar_bytes, sv.size(), sv.data(), name + " S x V");
  factors.pair_rows = pairs_in_rows ? std::move(u) : std::move(sv);
  factors.texel_rows = pairs_in_rows ? std::move(sv) : std::move(u);
  return factors;
}

class DfmfDecoder final : public ImageDecoder {
 public:
  DfmfDecoder(std::string file, Header header, ubo2014::ColourTransform colour,
              std::array<ChannelFactors, 3> channels)
      : file_(std::move(file)),
        header_(std::move(header)),
        colour_(colour),
        channels_(std::move(channels)),
        cosines_(light_cosines(header_)) {}

  void decode(LightView pair, std::span<float> rgb) const override {
    const std::size_t pair_index = std::size_t{pair.view} * header_.lights.size() + pair.light;
    for (std::size_t c = 0; c < 3; ++c) {
      const ChannelFactors& f = channels_[c];
      const float* coefficients = &f.pair_rows[pair_index * f.components];
      for (std::size_t t = 0; t < header_.texels(); ++t) {
        const float* row = &f.texel_rows[t * f.components];
        float sum = 0;
        for (std::uint32_t k = 0; k < f.components; ++k) sum += row[k] * coefficients[k];
        rgb[t * 3 + c] = sum;
      }
    }
    const float cosine = cosines_[pair.light];
    for (std::size_t t = 0; t < header_.texels(); ++t) {
      const auto value = ubo2014::to_rgb(colour_, {rgb[t * 3], rgb[t * 3 + 1], rgb[t * 3 + 2]});
      for (std::size_t c = 0; c < 3; ++c) {
        const float v = value[c] * cosine;
        if (!std::isfinite(v)) {
          throw InputError(file_,
                           "light " + std::to_string(pair.light) + ", view " + std::to_string(pair.view) +
                               ", texel (" + std::to_string(t % header_.width) + ", " +
                               std::to_string(t / header_.width) + ") decodes to a value that is not finite");
        }
        rgb[t * 3 + c] = std::max(v, 0.0f);
      }
    }
  }

  std::size_t storage_bytes() const override {
    std::size_t bytes = 0;
    for (const auto& f : channels_) bytes += (f.texel_rows.size() + f.pair_rows.size()) * sizeof(float);
    return bytes;
  }

 private:
  std::string file_;
  Header header_;
  ubo2014::ColourTransform colour_;
  std::array<ChannelFactors, 3> channels_;
  std::vector<float> cosines_;
};

BtfDataset read_dfmf(BoundedFile& file, Header header, std::vector<std::string>& warnings) {
  read_extent(file, header);
  skip_rotations(file);
  const auto max_components = file.value<std::uint32_t>("DFMF component count");
  const auto model = file.value<std::int32_t>("DFMF colour model");
  if (auto reason = ubo2014::unsupported_model(model)) file.fail("DFMF colour model", *reason);
  ubo2014::ColourTransform colour;
  colour.model = static_cast<ubo2014::ColourModel>(model);
  file.read(colour.mean.data(), sizeof colour.mean, "DFMF colour mean");
  file.read(colour.matrix.data(), sizeof colour.matrix, "DFMF colour matrix");
  for (float v : colour.mean)
    if (!std::isfinite(v)) file.fail("DFMF colour mean", "is not finite");
  for (float v : colour.matrix)
    if (!std::isfinite(v)) file.fail("DFMF colour matrix", "is not finite");

  std::array<ChannelFactors, 3> channels;
  for (std::uint32_t c = 0; c < 3; ++c) channels[c] = read_channel(file, header, c, max_components);
  if (file.remaining() != 0) {
    warnings.push_back(file.path().string() + ": " + std::to_string(file.remaining()) +
                       " bytes after the DFMF factors are ignored");
  }
  std::uint32_t components = 0;
  for (const auto& f : channels) components = std::max(components, f.components);
  const std::uint32_t width = header.width;
  const std::uint32_t height = header.height;
  std::vector<Direction> lights = header.lights;
  std::vector<Direction> views = header.views;
  auto decoder =
      std::make_shared<DfmfDecoder>(file.path().string(), std::move(header), colour, std::move(channels));
  BtfDataset dataset(std::move(lights), std::move(views), width, height, std::move(decoder));
  dataset.source = "UBO2014 DFMF file " + file.path().string() + " (" + std::to_string(components) +
                   " components, colour model " + std::to_string(model) + ")";
  return dataset;
}

// ---- BDI (raw) ----

BtfDataset read_bdi(BoundedFile& file, Header header, const BtfLoadOptions& options,
                    std::vector<std::string>& warnings) {
  read_extent(file, header);
  const auto scan_lines = file.value<std::uint32_t>("BDI scan lines per chunk");
  if (scan_lines == 0 || scan_lines > header.height) {
    file.fail("BDI scan lines per chunk",
              std::to_string(scan_lines) + " is not in 1-" + std::to_string(header.height) + " (the height)");
  }
  const auto compression = file.value<std::uint8_t>("BDI compression");
  if (compression == 1)
    file.fail("BDI compression",
              "bzip2-compressed chunks (1) are not read by carbtf; use a raw (0, 2) or DFMF file");
  if (compression != 0 && compression != 2)
    file.fail("BDI compression", std::to_string(compression) + " is none of 0 (full), 2 (sparse)");
  file.require(header.texels(), "BDI mask");
  std::vector<std::uint8_t> mask(header.texels());
  file.read(mask.data(), mask.size(), "BDI mask");
  skip_rotations(file);

  // The texels stored in order, x fastest: all of them (full) or the mask's (sparse).
  std::vector<std::uint32_t> stored;
  for (std::uint32_t t = 0; t < header.texels(); ++t) {
    if (compression == 0 || mask[t] != 0) stored.push_back(t);
  }
  if (stored.size() * ubo2014::kMinStoredShareDenominator < header.texels()) {
    file.fail("BDI mask", "stores " + std::to_string(stored.size()) + " of " +
                              std::to_string(header.texels()) + " texels; carbtf needs at least 1 in " +
                              std::to_string(ubo2014::kMinStoredShareDenominator));
  }
  const std::uint64_t abrdf_values = header.pairs() * 3;
  const std::uint64_t per_chunk = std::uint64_t{header.width} * scan_lines;
  const std::uint64_t chunks = (stored.size() + per_chunk - 1) / per_chunk;
  file.require(stored.size() * abrdf_values * 2 + chunks * 4, "BDI chunks");
  const std::uint64_t image_bytes = header.pairs() * header.texels() * 3 * 2;
  require_memory(file, image_bytes, "BDI images");

  std::vector<std::vector<std::uint16_t>> images(header.pairs(),
                                                 std::vector<std::uint16_t>(header.texels() * 3, 0));
  std::vector<std::uint16_t> chunk;
  const std::vector<float> cosines = light_cosines(header);
  Progress progress("reading " + std::to_string(chunks) + " BDI chunks", chunks, options.progress);
  for (std::uint64_t k = 0; k < chunks; ++k) {
    const std::uint64_t first = k * per_chunk;
    const std::uint64_t count = std::min<std::uint64_t>(per_chunk, stored.size() - first);
    const std::string name = "BDI chunk " + std::to_string(k);
    const auto bytes = file.value<std::uint32_t>(name + " size");
    if (bytes != count * abrdf_values * 2) {
      file.fail(name + " size", std::to_string(bytes) + " bytes where its " + std::to_string(count) +
                                    " texels of " + std::to_string(header.pairs()) +
                                    " light/view pairs take " + std::to_string(count * abrdf_values * 2));
    }
    chunk.resize(count * abrdf_values);
    file.read(chunk.data(), bytes, name);
    for (std::uint64_t a = 0; a < count; ++a) {
      const std::uint32_t texel = stored[first + a];
      const std::uint16_t* abrdf = &chunk[a * abrdf_values];
      for (std::size_t v = 0; v < header.views.size(); ++v) {
        for (std::size_t l = 0; l < header.lights.size(); ++l) {
          const std::uint16_t* value = &abrdf[(v * header.lights.size() + l) * 3];
          std::uint16_t* out = &images[l * header.views.size() + v][std::size_t{texel} * 3];
          const float cosine = cosines[l];
          for (int c = 0; c < 3; ++c) {
            if (!half_is_finite(value[c])) {
              file.fail(name, "light " + std::to_string(l) + ", view " + std::to_string(v) + ", texel (" +
                                  std::to_string(texel % header.width) + ", " +
                                  std::to_string(texel / header.width) + ") is not a finite number");
            }
            std::uint16_t bits = (value[c] & 0x8000u) ? 0 : value[c];  // negative: 0
            if (cosine != 1.0f && bits != 0) {
              Imath::half h;
              h.setBits(bits);
              bits = Imath::half(static_cast<float>(h) * cosine).bits();
            }
            out[c] = bits;
          }
        }
      }
    }
    progress.advance();
  }
  if (file.remaining() != 0) {
    warnings.push_back(file.path().string() + ": " + std::to_string(file.remaining()) +
                       " bytes after the BDI chunks are ignored");
  }
  BtfDataset dataset(header.lights, header.views, header.width, header.height, ColorEncoding::linear_half);
  for (std::uint32_t l = 0; l < header.lights.size(); ++l) {
    for (std::uint32_t v = 0; v < header.views.size(); ++v) {
      dataset.set_linear_half({l, v}, std::move(images[std::size_t{l} * header.views.size() + v]));
    }
  }
  if (stored.size() < header.texels()) {
    dataset.mask.resize(header.texels());
    for (std::size_t t = 0; t < mask.size(); ++t) dataset.mask[t] = mask[t] != 0 ? 255 : 0;
  }
  dataset.source = "UBO2014 raw (BDI) file " + file.path().string();
  return dataset;
}

}  // namespace

BtfDataset read_ubo2014_btf(const std::filesystem::path& path, const BtfLoadOptions& options,
                            std::vector<std::string>& warnings) {
  BoundedFile file(path);
  Header header;
  header.layout = read_signature(file);
  read_meta_data(file, header);
  read_directions(file, header, warnings);
  return header.layout == ubo2014::Layout::dfmf ? read_dfmf(file, std::move(header), warnings)
                                                : read_bdi(file, std::move(header), options, warnings);
}

}  // namespace carbtf
