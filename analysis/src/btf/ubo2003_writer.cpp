#include "carbtf/analysis/btf/ubo2003_writer.hpp"

#include <zip.h>

#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "carbtf/analysis/btf/ubo2003_names.hpp"
#include "carbtf/analysis/image_io.hpp"
#include "carbtf/analysis/input_error.hpp"
#include "zip_error.hpp"

namespace carbtf {

struct Ubo2003Writer::Archive {
  zip_t* handle = nullptr;
};

Ubo2003Writer::Ubo2003Writer(std::filesystem::path output, std::string extension, bool zip)
    : output_(std::move(output)), extension_(std::move(extension)) {
  if (zip) {
    create_folder(output_.parent_path());
    if (const Status s = check_output_file(output_.string()); !s.ok()) throw std::runtime_error(s.message());
    int error = 0;
    archive_ = std::make_unique<Archive>();
    archive_->handle = zip_open(output_.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
    if (!archive_->handle)
      throw InputError(output_, "cannot create archive: " + detail::zip_error_text(error));
  } else {
    create_folder(output_);
  }
}

Ubo2003Writer::~Ubo2003Writer() {
  if (archive_ && archive_->handle) zip_discard(archive_->handle);
}

void Ubo2003Writer::write(std::uint32_t light, std::uint32_t view, std::span<const float> linear_rgb,
                          std::uint32_t width, std::uint32_t height) {
  const std::string entry = ubo2003_view_folder(view) + "/" + ubo2003_file_name(light, view, extension_);
  std::vector<std::byte> encoded = encode_rgb_image(entry, linear_rgb, width, height);
  if (archive_) {
    // libzip frees the buffer (last argument 1) once the archive is written.
    void* copy = std::malloc(encoded.size());
    if (!copy) throw std::bad_alloc();
    std::memcpy(copy, encoded.data(), encoded.size());
    std::lock_guard<std::mutex> lock(mutex_);
    zip_source_t* source = zip_source_buffer(archive_->handle, copy, encoded.size(), 1);
    if (!source) {
      std::free(copy);
      throw InputError(output_, "cannot add " + entry + ": " + zip_strerror(archive_->handle));
    }
    if (zip_file_add(archive_->handle, entry.c_str(), source, ZIP_FL_OVERWRITE | ZIP_FL_ENC_UTF_8) < 0) {
      zip_source_free(source);
      throw InputError(output_, "cannot add " + entry + ": " + zip_strerror(archive_->handle));
    }
    return;
  }
  write_output_file(output_ / entry, encoded, Flush::later);  // flushed once, by finish()
}

void Ubo2003Writer::finish() {
  if (!archive_) {
    // The images skipped a flush each (Flush::later): one for all of them.
    if (const Status s = flush_file_system(output_.string()); !s.ok()) throw std::runtime_error(s.message());
    return;
  }
  if (!archive_->handle) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (zip_close(archive_->handle) < 0) {
    const std::string message = zip_strerror(archive_->handle);
    zip_discard(archive_->handle);
    archive_->handle = nullptr;
    throw InputError(output_, "cannot write archive: " + message);
  }
  archive_->handle = nullptr;
}

}  // namespace carbtf
