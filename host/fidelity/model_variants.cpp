#include "fidelity/model_variants.hpp"

namespace carbtf::cli {

const std::vector<ModelVariant>& model_variants() {
  static const std::vector<ModelVariant> variants{
      {"paper", "no relief tone, 64-texel tiles, 16-bit heights (the model before issue 13)",
       [](AnalysisOptions& o) {
         o.relief_tone = false;
         o.tiles.tile_size = 64;
         o.tiles.height_bits = 16;
       }},
      {"tiles128", "no relief tone, 128-texel tiles", [](AnalysisOptions& o) { o.relief_tone = false; }},
      {"tone64", "relief tone, 64-texel tiles", [](AnalysisOptions& o) { o.tiles.tile_size = 64; }},
      {"tone96", "relief tone, 96-texel tiles", [](AnalysisOptions& o) { o.tiles.tile_size = 96; }},
      {"tone128_12bit", "relief tone, 128-texel tiles, 12-bit heights",
       [](AnalysisOptions& o) { o.tiles.height_bits = 12; }},
      {"fine", "the default with 8-bit heights and a 7-bit tone (the default before format 1.5)",
       [](AnalysisOptions& o) {
         o.tiles.height_bits = 8;
         o.tiles.tone_bits = 7;
         o.tiles.colour_tone_bits = 7;
       }},
      {"compact", "the default with 5-bit heights and a 3-bit tone (colour planes 4-bit)",
       [](AnalysisOptions& o) {
         o.tiles.height_bits = 5;
         o.tiles.tone_bits = 3;
         o.tiles.colour_tone_bits = 4;
       }},
      {"default",
       "relief tone (R, G, B planes where its colour is not grey), 128-texel tiles with feathered cuts, "
       "the best-looking of 8 tilings, 6-bit heights, the tone band-limited where the models look nearer, "
       "4-bit grey tone or 6-bit colour planes; clamp, levels and noise gains per scale chosen per subspace",
       [](AnalysisOptions&) {}},
      {"specular", "the default with the relief's specular lobe wherever it is fitted (--specular)",
       [](AnalysisOptions& o) { o.relief_specular = AutoChoice::always; }},
      {"no_specular", "the default without the relief's specular lobe",
       [](AnalysisOptions& o) { o.relief_specular = AutoChoice::never; }},
      {"deshade", "the default with the relit range map divided out (floor 0.3)",
       [](AnalysisOptions& o) { o.deshade_floor = 0.3; }},
      {"no_pair_gains", "the default without the per-pair colour gains",
       [](AnalysisOptions& o) { o.pair_gains = false; }},
      {"no_noise_gains", "the default with every subspace's fitted sigma",
       [](AnalysisOptions& o) {
         o.noise_gains = {1.0};
         o.noise_raises = {1.0};
         o.chroma_raises = {1.0};
       }},
      {"four_bit_colour_tone", "the default with its colour tone planes at 4 bits, as the grey tone",
       [](AnalysisOptions& o) { o.tiles.colour_tone_bits = 4; }},
      {"uniform_noise_gains", "the default with its noise gains on every pyramid level alike",
       [](AnalysisOptions& o) { o.gains_per_scale = false; }},
      {"grey_tone", "the default with a grey relief tone everywhere",
       [](AnalysisOptions& o) { o.tone_planes = TonePlanes::never; }},
      {"hard_cuts", "the default with hard range-tile cuts", [](AnalysisOptions& o) { o.tiles.feather = 0; }},
      {"tone_weights",
       "the default with each subspace's share of the relief tone (0 or 1) chosen with its clamp",
       [](AnalysisOptions& o) {
         o.tone_weights = {0.0, 1.0};
       }},
      {"fixed_levels", "the default with 3 pyramid levels in every subspace",
       [](AnalysisOptions& o) { o.other_level_counts = {}; }},
      {"no_shadows", "the default without the relief's cast shadows",
       [](AnalysisOptions& o) { o.relief_shadows = AutoChoice::never; }},
      {"usual_stereo", "the default without photometric stereo's strict rejection of shadowed samples",
       [](AnalysisOptions& o) { o.strict_stereo = AutoChoice::never; }},
      {"strict_stereo",
       "the default with photometric stereo's strict rejection of shadowed samples everywhere",
       [](AnalysisOptions& o) { o.strict_stereo = AutoChoice::always; }},
      {"one_tiling", "the default with the range tiles' first draw, unscored (before the tiling choice)",
       [](AnalysisOptions& o) { o.tiling_candidates = 1; }},
      {"shadows", "the default with the relief's cast shadows at full strength",
       [](AnalysisOptions& o) { o.relief_shadows = AutoChoice::always; }},
      {"sharp_tone", "the default with the relief tone as measured, never band-limited",
       [](AnalysisOptions& o) { o.tone_band_limit = AutoChoice::never; }},
      {"band_limited_tone", "the default with the relief tone band-limited on every material",
       [](AnalysisOptions& o) { o.tone_band_limit = AutoChoice::always; }},
  };
  return variants;
}

}  // namespace carbtf::cli
