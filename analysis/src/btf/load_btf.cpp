// load_btf(): picks the reader by what the path is.
#include "../text.hpp"
#include "carbtf/analysis/btf/btf_reader.hpp"
#include "carbtf/analysis/btf/ubo2003_zip_reader.hpp"
#include "carbtf/analysis/input_error.hpp"

namespace carbtf {

BtfDataset load_btf(const std::filesystem::path& path, const BtfLoadOptions& options,
                    std::vector<std::string>& warnings) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(path, "no such file or folder");
  if (std::filesystem::is_directory(path, ec)) {
    if (std::filesystem::exists(path / "light_directions.txt", ec))
      return read_photometric_stereo(path, options, warnings);
    return read_ubo2003_folder(path, options, warnings);
  }
  const std::string extension = detail::lower_extension(path);
  if (extension == ".zip") return read_ubo2003_zip(path, options, warnings);
  if (extension == ".csv") return read_manifest(path, options, warnings);
  if (extension == ".btf") return read_ubo2014_btf(path, options, warnings);
  throw InputError(path,
                   "not a BTF dataset: expected a UBO2003 folder or .zip, a manifest .csv, a "
                   "photometric-stereo folder, or a UBO2014 .btf file");
}

}  // namespace carbtf
