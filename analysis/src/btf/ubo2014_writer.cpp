#include "carbtf/analysis/btf/ubo2014_writer.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <Imath/half.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "carbtf/engine/file_output.hpp"
#include "ubo2014_colour.hpp"

namespace carbtf {

namespace {

// Writes beside the target, flushes to the disk and renames over it when done, as every carbtf output
// (carbtf/engine/file_output.hpp): a failed write leaves the target as it was and no temporary behind;
// a target that is not a regular file is refused; a symbolic link to one is written through and kept,
// and a replaced file keeps its permission bits. Streamed, for files of gigabytes.
class BinaryOut {
 public:
  explicit BinaryOut(const std::filesystem::path& path) : path_(path) {
    if (const Status status = check_output_file(path.string()); !status.ok())
      throw std::runtime_error(status.message());
    std::error_code ec;
    target_ = std::filesystem::is_symlink(path, ec) ? std::filesystem::canonical(path) : path;
    temporary_ = target_.string() + ".carbtf-" + std::to_string(getpid()) + ".tmp";
    fd_ = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd_ < 0) fail("cannot be created");
    if (std::filesystem::exists(target_, ec)) {
      std::filesystem::permissions(temporary_, std::filesystem::status(target_).permissions(), ec);
    }
  }
  ~BinaryOut() {
    if (fd_ >= 0) ::close(fd_);
    if (!finished_) ::unlink(temporary_.c_str());
  }
  BinaryOut(const BinaryOut&) = delete;
  BinaryOut& operator=(const BinaryOut&) = delete;

  template <class T>
  void value(T v) {
    bytes(&v, sizeof v);
  }
  void bytes(const void* data, std::size_t size) {
    const auto* at = static_cast<const char*>(data);
    while (size > 0) {
      const ssize_t written = ::write(fd_, at, std::min<std::size_t>(size, 1u << 30));
      if (written < 0 && errno == EINTR) continue;
      if (written <= 0) fail("write failed");
      at += written;
      size -= static_cast<std::size_t>(written);
    }
  }
  void text(const std::string& s, std::size_t size) {
    std::string padded = s;
    padded.resize(size, '\0');
    bytes(padded.data(), size);
  }
  void scalars(const float* values, std::size_t count, std::uint8_t scalar_bytes) {
    if (scalar_bytes == 4) return bytes(values, count * 4);
    std::vector<std::uint16_t> halves(count);
    for (std::size_t i = 0; i < count; ++i) halves[i] = Imath::half(values[i]).bits();
    bytes(halves.data(), count * 2);
  }
  void finish() {
    if (::fsync(fd_) != 0) fail("flush to the disk failed");
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) fail("close failed");
    if (::rename(temporary_.c_str(), target_.c_str()) != 0) fail("cannot replace it");
    finished_ = true;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error(path_.string() + ": " + what + " (" + std::strerror(errno) + ")");
  }

  std::filesystem::path path_;
  std::filesystem::path target_;
  std::filesystem::path temporary_;
  int fd_ = -1;
  bool finished_ = false;
};

void write_header(BinaryOut& out, const BtfDataset& dataset, const Ubo2014WriteOptions& options) {
  out.bytes(
      (options.layout == ubo2014::Layout::dfmf ? ubo2014::kDfmfSignature : ubo2014::kBdiSignature).data(),
      10);
  const std::uint32_t meta_size = 4 + 4 + 3 * 80 + 4 + 3 * 4 + 4 + 4 + 4 + 3 * (4 + 1);
  out.value(meta_size);
  out.value(std::uint32_t{4});
  out.text("carbtf", 80);
  out.text("", 80);
  out.text("", 80);
  out.value(0.0f);
  for (int c = 0; c < 3; ++c) out.value(1.0f);
  out.value(std::uint32_t{options.cosine_in_data ? 1u : 0u});
  out.value(std::uint32_t{0});  // no XML
  out.value(std::uint32_t{3});
  for (const char* name : {"R", "G", "B"}) {
    out.value(std::uint32_t{1});
    out.bytes(name, 1);
  }
  out.value(static_cast<std::uint32_t>(dataset.views().size()));
  for (const Direction& view : dataset.views()) {
    out.value(static_cast<float>(view.theta));
    out.value(static_cast<float>(view.phi));
    out.value(static_cast<std::uint32_t>(dataset.lights().size()));
    for (const Direction& light : dataset.lights()) {
      out.value(static_cast<float>(light.theta));
      out.value(static_cast<float>(light.phi));
    }
  }
  out.value(dataset.width());
  out.value(dataset.height());
}

// A pair's image as the file stores it: linear RGB, divided by the light's cosine where the flag says
// the data lacks it.
void stored_image(const BtfDataset& dataset, const Ubo2014WriteOptions& options, LightView pair,
                  std::vector<float>& rgb) {
  rgb.resize(dataset.pixel_count() * 3);
  if (!dataset.has_image(pair))
    throw std::invalid_argument("write_ubo2014_btf: the dataset misses a light/view pair");
  dataset.linear_rgb(pair, rgb);
  if (!options.cosine_in_data) {
    const float cosine = static_cast<float>(std::cos(dataset.lights()[pair.light].theta));
    for (float& v : rgb) v /= cosine;
  }
}

std::vector<LightView> pairs_in_file_order(const BtfDataset& dataset) {  // light fastest
  std::vector<LightView> pairs;
  for (std::uint32_t v = 0; v < dataset.views().size(); ++v) {
    for (std::uint32_t l = 0; l < dataset.lights().size(); ++l) pairs.push_back({l, v});
  }
  return pairs;
}

// ---- DFMF ----

struct Decorrelation {
  ubo2014::ColourTransform inverse;  // what the file records (channels to RGB)
  Eigen::Matrix3f forward;           // RGB (minus mean) to channels
  Eigen::Vector3f mean = Eigen::Vector3f::Zero();
};

Decorrelation decorrelation(const BtfDataset& dataset, const Ubo2014WriteOptions& options) {
  Decorrelation d;
  d.inverse.model = options.colour_model;
  switch (options.colour_model) {
    case ubo2014::ColourModel::rgb:
      d.forward.setIdentity();
      break;
    case ubo2014::ColourModel::yuv: {
      Eigen::Matrix3f to_rgb;
      for (int i = 0; i < 3; ++i) {
        std::array<float, 3> unit{};
        unit[i] = 1;
        const auto column = ubo2014::yuv_to_rgb(unit[0], unit[1], unit[2]);
        to_rgb.col(i) = Eigen::Vector3f(column[0], column[1], column[2]);
      }
      d.forward = to_rgb.inverse();
      break;
    }
    case ubo2014::ColourModel::pca: {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      Eigen::Matrix3d products = Eigen::Matrix3d::Zero();
      std::vector<float> rgb;
      double n = 0;
      for (const LightView pair : pairs_in_file_order(dataset)) {
        stored_image(dataset, options, pair, rgb);
        for (std::size_t t = 0; t < dataset.pixel_count(); ++t) {
          const Eigen::Vector3d x(rgb[t * 3], rgb[t * 3 + 1], rgb[t * 3 + 2]);
          sum += x;
          products += x * x.transpose();
          n += 1;
        }
      }
      const Eigen::Vector3d mean = sum / n;
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(products / n - mean * mean.transpose());
      for (int i = 0; i < 3; ++i) {
        const Eigen::Vector3d axis = solver.eigenvectors().col(2 - i);  // largest variance first
        d.forward.row(i) = axis.cast<float>().transpose();
        for (int j = 0; j < 3; ++j) d.inverse.matrix[i * 3 + j] = static_cast<float>(axis[j]);
        d.inverse.mean[i] = static_cast<float>(mean[i]);
      }
      d.mean = mean.cast<float>();
      break;
    }
    default:
      throw std::invalid_argument("write_ubo2014_btf: carbtf writes colour models rgb, yuv and pca only");
  }
  return d;
}

// One channel's values of a pair's image, decorrelated: out[c][t].
void channel_rows(const BtfDataset& dataset, const Ubo2014WriteOptions& options, const Decorrelation& d,
                  LightView pair, std::vector<float>& rgb, std::array<std::vector<float>, 3>& out) {
  stored_image(dataset, options, pair, rgb);
  for (auto& channel : out) channel.resize(dataset.pixel_count());
  for (std::size_t t = 0; t < dataset.pixel_count(); ++t) {
    const Eigen::Vector3f c =
        d.forward * (Eigen::Vector3f(rgb[t * 3], rgb[t * 3 + 1], rgb[t * 3 + 2]) - d.mean);
    for (int i = 0; i < 3; ++i) out[i][t] = c[i];
  }
}

struct Factors {  // row-major
  std::uint32_t components = 0;
  std::vector<float> singular;
  std::vector<float> pair_rows;   // pairs x components (U)
  std::vector<float> texel_rows;  // texels x components (S x V)
};

std::array<Factors, 3> exact_factors(const BtfDataset& dataset, const Ubo2014WriteOptions& options,
                                     const Decorrelation& d) {
  const auto pairs = pairs_in_file_order(dataset);
  const std::size_t n = pairs.size();
  const std::size_t texels = dataset.pixel_count();
  if (n > texels)
    throw std::invalid_argument(
        "write_ubo2014_btf: exact DFMF needs at least as many texels as light/view pairs");
  std::array<Factors, 3> f;
  for (auto& channel : f) {
    channel.components = static_cast<std::uint32_t>(n);
    channel.singular.assign(n, 1.0f);
    channel.pair_rows.assign(n * n, 0.0f);
    for (std::size_t i = 0; i < n; ++i) channel.pair_rows[i * n + i] = 1.0f;
    channel.texel_rows.resize(texels * n);
  }
  std::vector<float> rgb;
  std::array<std::vector<float>, 3> rows;
  for (std::size_t p = 0; p < n; ++p) {
    channel_rows(dataset, options, d, pairs[p], rgb, rows);
    for (int c = 0; c < 3; ++c) {
      for (std::size_t t = 0; t < texels; ++t) f[c].texel_rows[t * n + p] = rows[c][t];
    }
  }
  return f;
}

// A randomised range finder (Halko, Martinsson & Tropp 2011) with 8 extra columns and no power
// iteration: a BTF's spectrum falls fast. Two passes over the images; the data matrix is never held.
std::array<Factors, 3> truncated_factors(const BtfDataset& dataset, const Ubo2014WriteOptions& options,
                                         const Decorrelation& d) {
  const auto pairs = pairs_in_file_order(dataset);
  const Eigen::Index n = static_cast<Eigen::Index>(pairs.size());
  const Eigen::Index texels = static_cast<Eigen::Index>(dataset.pixel_count());
  const Eigen::Index k = std::min<Eigen::Index>({options.components, n, texels});
  const Eigen::Index sketch = std::min<Eigen::Index>({k + 8, n, texels});
  std::mt19937_64 random(options.seed);
  std::normal_distribution<float> gaussian;
  Eigen::MatrixXf omega(texels, sketch);
  for (Eigen::Index j = 0; j < sketch; ++j) {
    for (Eigen::Index i = 0; i < texels; ++i) omega(i, j) = gaussian(random);
  }
  std::vector<float> rgb;
  std::array<std::vector<float>, 3> rows;
  std::array<Eigen::MatrixXd, 3> y;
  for (auto& m : y) m.resize(n, sketch);
  for (Eigen::Index p = 0; p < n; ++p) {
    channel_rows(dataset, options, d, pairs[static_cast<std::size_t>(p)], rgb, rows);
    for (int c = 0; c < 3; ++c) {
      y[c].row(p) = (Eigen::Map<const Eigen::RowVectorXf>(rows[c].data(), texels) * omega).cast<double>();
    }
  }
  std::array<Eigen::MatrixXd, 3> q, b;
  for (int c = 0; c < 3; ++c) {
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(y[c]);
    q[c] = qr.householderQ() * Eigen::MatrixXd::Identity(n, sketch);
    b[c] = Eigen::MatrixXd::Zero(sketch, texels);
  }
  for (Eigen::Index p = 0; p < n; ++p) {
    channel_rows(dataset, options, d, pairs[static_cast<std::size_t>(p)], rgb, rows);
    for (int c = 0; c < 3; ++c) {
      b[c].noalias() += q[c].row(p).transpose() *
                        Eigen::Map<const Eigen::RowVectorXf>(rows[c].data(), texels).cast<double>();
    }
  }
  std::array<Factors, 3> f;
  for (int c = 0; c < 3; ++c) {
    const Eigen::BDCSVD<Eigen::MatrixXd> svd(b[c], Eigen::ComputeThinU | Eigen::ComputeThinV);
    const Eigen::MatrixXd u = q[c] * svd.matrixU().leftCols(k);
    const Eigen::MatrixXd sxv = svd.matrixV().leftCols(k) * svd.singularValues().head(k).asDiagonal();
    f[c].components = static_cast<std::uint32_t>(k);
    f[c].singular.resize(static_cast<std::size_t>(k));
    for (Eigen::Index i = 0; i < k; ++i)
      f[c].singular[static_cast<std::size_t>(i)] = static_cast<float>(svd.singularValues()[i]);
    const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> u_rows = u.cast<float>();
    const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> sxv_rows = sxv.cast<float>();
    f[c].pair_rows.assign(u_rows.data(), u_rows.data() + u_rows.size());
    f[c].texel_rows.assign(sxv_rows.data(), sxv_rows.data() + sxv_rows.size());
  }
  return f;
}

void write_dfmf(BinaryOut& out, const BtfDataset& dataset, const Ubo2014WriteOptions& options) {
  if (options.scalar_bytes != 2 && options.scalar_bytes != 4)
    throw std::invalid_argument("write_ubo2014_btf: scalars of 2 or 4 bytes");
  out.value(std::uint32_t{0});  // no rotations
  const Decorrelation d = decorrelation(dataset, options);
  const std::array<Factors, 3> factors =
      options.components == 0 ? exact_factors(dataset, options, d) : truncated_factors(dataset, options, d);
  out.value(factors[0].components);
  out.value(static_cast<std::int32_t>(options.colour_model));
  out.bytes(d.inverse.mean.data(), sizeof d.inverse.mean);
  out.bytes(d.inverse.matrix.data(), sizeof d.inverse.matrix);
  const auto pairs = static_cast<std::uint32_t>(dataset.lights().size() * dataset.views().size());
  for (const Factors& f : factors) {
    out.value(options.scalar_bytes);
    out.value(f.components);
    out.value(pairs);
    out.value(static_cast<std::uint32_t>(dataset.pixel_count()));
    out.scalars(f.singular.data(), f.singular.size(), options.scalar_bytes);
    out.scalars(f.pair_rows.data(), f.pair_rows.size(), options.scalar_bytes);
    out.scalars(f.texel_rows.data(), f.texel_rows.size(), options.scalar_bytes);
  }
}

// ---- BDI ----

void write_bdi(BinaryOut& out, const BtfDataset& dataset, const Ubo2014WriteOptions& options) {
  const std::uint32_t scan_lines =
      std::clamp<std::uint32_t>(options.scan_lines_per_chunk, 1, dataset.height());
  const bool sparse = options.sparse && !dataset.mask.empty();
  out.value(scan_lines);
  out.value(std::uint8_t{sparse ? std::uint8_t{2} : std::uint8_t{0}});
  std::vector<std::uint8_t> mask(dataset.pixel_count(), 1);
  if (sparse) {
    for (std::size_t t = 0; t < mask.size(); ++t) mask[t] = dataset.mask[t] != 0 ? 1 : 0;
  }
  out.bytes(mask.data(), mask.size());
  out.value(std::uint32_t{0});  // no rotations
  std::vector<std::uint32_t> stored;
  for (std::uint32_t t = 0; t < mask.size(); ++t) {
    if (mask[t]) stored.push_back(t);
  }
  const auto pairs = pairs_in_file_order(dataset);
  const std::size_t abrdf_values = pairs.size() * 3;
  const std::size_t per_chunk = std::size_t{dataset.width()} * scan_lines;
  // Whole chunks at a time, as many as fit 256 MiB of halves: each image is decoded once per group.
  const std::size_t chunks_per_group =
      std::max<std::size_t>(1, (std::size_t{128} << 20) / (per_chunk * abrdf_values));
  std::vector<float> rgb;
  std::vector<std::uint16_t> group;
  for (std::size_t first = 0; first < stored.size(); first += chunks_per_group * per_chunk) {
    const std::size_t count = std::min(chunks_per_group * per_chunk, stored.size() - first);
    group.assign(count * abrdf_values, 0);
    for (std::size_t p = 0; p < pairs.size(); ++p) {
      stored_image(dataset, options, pairs[p], rgb);
      for (std::size_t a = 0; a < count; ++a) {
        for (int c = 0; c < 3; ++c)
          group[a * abrdf_values + p * 3 + c] =
              Imath::half(rgb[std::size_t{stored[first + a]} * 3 + c]).bits();
      }
    }
    for (std::size_t a = 0; a < count; a += per_chunk) {
      const std::size_t in_chunk = std::min(per_chunk, count - a);
      out.value(static_cast<std::uint32_t>(in_chunk * abrdf_values * 2));
      out.bytes(&group[a * abrdf_values], in_chunk * abrdf_values * 2);
    }
  }
}

}  // namespace

void write_ubo2014_btf(const std::filesystem::path& path, const BtfDataset& dataset,
                       const Ubo2014WriteOptions& options) {
  BinaryOut out(path);
  write_header(out, dataset, options);
  if (options.layout == ubo2014::Layout::dfmf) {
    write_dfmf(out, dataset, options);
  } else {
    write_bdi(out, dataset, options);
  }
  out.finish();
}

}  // namespace carbtf
