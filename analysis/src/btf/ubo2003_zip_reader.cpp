// The UBO2003 layout inside a .zip archive. Entries are read into memory, never extracted, and any
// entry whose name is absolute or climbs out with ".." is refused as hostile.
#include <zip.h>
#include <zlib.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>
#include <mutex>

#include "carbtf/analysis/btf/ubo2003_names.hpp"
#include "carbtf/analysis/btf/ubo2003_zip_reader.hpp"
#include "carbtf/analysis/input_error.hpp"
#include "image_sources.hpp"
#include "ubo2003_entries.hpp"
#include "zip_error.hpp"

namespace carbtf {

namespace {

// No BTF image comes near this; a larger entry is a zip bomb or garbage.
constexpr zip_uint64_t kMaxEntryBytes = 256ull << 20;

struct ZipArchive {
  zip_t* handle = nullptr;
  std::mutex mutex;  // libzip handles are not thread-safe
  ~ZipArchive() {
    if (handle) zip_discard(handle);
  }
};

bool hostile_entry_name(const std::string& name) {
  if (name.empty() || name[0] == '/' || name[0] == '\\') return true;
  if (name.size() > 1 && name[1] == ':') return true;  // C:\...
  std::size_t start = 0;
  while (start <= name.size()) {
    const std::size_t end = name.find_first_of("/\\", start);
    const std::string part = name.substr(start, end == std::string::npos ? std::string::npos : end - start);
    if (part == "..") return true;
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return false;
}

// An entry's bytes, checked against the size and CRC-32 its header records: libzip checks the CRC only
// when a read reaches the end, and a stored entry with a wrong CRC would otherwise pass unnoticed.
std::vector<std::byte> read_checked_entry(ZipArchive& archive, zip_uint64_t index, zip_uint64_t size,
                                          zip_uint32_t crc, const std::string& display) {
  std::lock_guard<std::mutex> lock(archive.mutex);
  zip_file_t* file = zip_fopen_index(archive.handle, index, 0);
  if (!file) throw InputError(display, std::string("cannot open entry: ") + zip_strerror(archive.handle));
  std::vector<std::byte> bytes(static_cast<std::size_t>(size));
  const zip_int64_t got = zip_fread(file, bytes.data(), size);
  std::byte past_end{};
  const zip_int64_t more =
      got < 0 ? 0 : zip_fread(file, &past_end, 1);  // reaching the end lets libzip check too
  const std::string library_error = zip_file_strerror(file);
  const bool crc_error = zip_error_code_zip(zip_file_get_error(file)) == ZIP_ER_CRC;
  zip_fclose(file);
  if (crc_error)
    throw InputError(
        display,
        "CRC-32 mismatch: the data does not give the CRC its header records; the archive is corrupt");
  if (got < 0 || more < 0) throw InputError(display, "entry is corrupt (" + library_error + ")");
  if (static_cast<zip_uint64_t>(got) != size || more != 0) {
    throw InputError(display, "entry holds " + std::string(more != 0 ? "more" : "fewer") +
                                  " bytes than the " + std::to_string(size) + " its header records");
  }
  uLong actual = crc32(0L, Z_NULL, 0);
  for (std::size_t at = 0; at < bytes.size();) {
    const auto chunk = static_cast<uInt>(std::min<std::size_t>(bytes.size() - at, 1u << 30));
    actual = crc32(actual, reinterpret_cast<const Bytef*>(bytes.data() + at), chunk);
    at += chunk;
  }
  if (static_cast<zip_uint32_t>(actual) != crc) {
    char text[96];
    std::snprintf(text, sizeof text, "CRC-32 mismatch: the data gives %08lx, the header records %08x", actual,
                  static_cast<unsigned>(crc));
    throw InputError(display, std::string(text) + "; the archive is corrupt");
  }
  return bytes;
}

}  // namespace

BtfDataset read_ubo2003_zip(const std::filesystem::path& archive_path, const BtfLoadOptions& options,
                            std::vector<std::string>& warnings) {
  auto archive = std::make_shared<ZipArchive>();
  int error = 0;
  archive->handle = zip_open(archive_path.c_str(), ZIP_RDONLY | ZIP_CHECKCONS, &error);
  if (!archive->handle) {
    throw InputError(archive_path, "not a readable zip archive (" + detail::zip_error_text(error) + ")");
  }
  const zip_int64_t count = zip_get_num_entries(archive->handle, 0);
  std::map<std::uint32_t, std::string> seen;
  std::vector<detail::ImageSource> sources;
  for (zip_int64_t i = 0; i < count; ++i) {
    zip_stat_t stat;
    if (zip_stat_index(archive->handle, static_cast<zip_uint64_t>(i), 0, &stat) != 0 ||
        !(stat.valid & ZIP_STAT_NAME)) {
      throw InputError(archive_path, "unreadable entry " + std::to_string(i));
    }
    const std::string name = stat.name;
    const std::string display = archive_path.string() + ":" + name;
    if (hostile_entry_name(name))
      throw InputError(display, "entry has an absolute or '..' path; refusing the archive");
    if (name.back() == '/') continue;  // a folder entry
    const std::size_t slash = name.find_last_of('/');
    const std::string file_name = slash == std::string::npos ? name : name.substr(slash + 1);
    if (file_name.starts_with(".") || name.starts_with("__MACOSX/")) continue;
    std::string folder_name;
    if (slash != std::string::npos) {
      const std::size_t previous = name.find_last_of('/', slash - 1);
      folder_name = name.substr(previous == std::string::npos ? 0 : previous + 1,
                                slash - (previous == std::string::npos ? 0 : previous + 1));
      int theta = 0, phi = 0;
      if (!parse_ubo2003_view_folder(folder_name, theta, phi)) folder_name.clear();  // an enclosing folder
    }
    if ((stat.valid & ZIP_STAT_SIZE) && stat.size > kMaxEntryBytes) {
      throw InputError(display,
                       "entry is " + std::to_string(stat.size >> 20) + " MiB, too large for a BTF image");
    }
    const LightView pair = detail::ubo2003_pair(display, file_name, folder_name, seen);
    if (!(stat.valid & ZIP_STAT_SIZE) || !(stat.valid & ZIP_STAT_CRC)) {
      throw InputError(display, "entry has no recorded size or CRC-32; refusing data that cannot be checked");
    }
    const auto index = static_cast<zip_uint64_t>(i);
    sources.push_back({display,
                       [archive, index, size = stat.size, crc = stat.crc, display] {
                         return read_checked_entry(*archive, index, size, crc, display);
                       },
                       pair});
  }
  if (sources.empty()) throw InputError(archive_path, "archive holds no images");
  return detail::decode_sources(sources, ubo2003_directions(), ubo2003_directions(),
                                "UBO2003 zip " + archive_path.string(), options, warnings);
}

}  // namespace carbtf
