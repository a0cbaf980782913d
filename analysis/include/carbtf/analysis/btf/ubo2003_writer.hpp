// Writes BTF images in the UBO2003 layout: into a folder (with per-view folders tvTTT_pvPPP, as the
// Bonn database ships them) or into a .zip with the same entry names. write() may be called from
// several threads at once for different pairs. Nothing is written outside the output path.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <span>
#include <string>

namespace carbtf {

class Ubo2003Writer {
 public:
  // `extension` is ".jpg", ".png" or ".exr". With `zip`, `output` is the archive file to create;
  // otherwise the folder to create (it may exist; files of the same names are replaced).
  Ubo2003Writer(std::filesystem::path output, std::string extension, bool zip);
  ~Ubo2003Writer();  // closes the archive if finish() was not called (errors are lost then)

  Ubo2003Writer(const Ubo2003Writer&) = delete;
  Ubo2003Writer& operator=(const Ubo2003Writer&) = delete;

  // Writes the image of UBO2003 light index `light` and view index `view` (0..80), linear RGB.
  void write(std::uint32_t light, std::uint32_t view, std::span<const float> linear_rgb, std::uint32_t width,
             std::uint32_t height);
  // Finishes the archive (zip mode), or flushes the folder's images to the disk; throws when the
  // archive cannot be written or the disk reports an error.
  void finish();

 private:
  struct Archive;
  std::filesystem::path output_;
  std::string extension_;
  std::unique_ptr<Archive> archive_;
  std::mutex mutex_;
};

}  // namespace carbtf
