#include "asset/mtl_reader.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

#include "asset/float_range.h"
#include "mesh/mesh_readers.h"
#include "mesh/text_scanner.h"

namespace meshwave {
namespace {

// Arity of the texture options (MTL specification, "Texture map
// statements"); -o, -s and -t take one to three numbers.
int OptionArity(std::string_view option) {
  if (option == "-blendu" || option == "-blendv" || option == "-cc" ||
      option == "-clamp" || option == "-bm" || option == "-boost" ||
      option == "-texres" || option == "-imfchan" || option == "-type") {
    return 1;
  }
  if (option == "-mm") return 2;
  if (option == "-o" || option == "-s" || option == "-t") return 3;
  return -1;
}

bool IsNumber(std::string_view token) {
  double ignored = 0.0;
  return ParseDouble(token, &ignored);
}

struct TextureStatement {
  std::string file;  // resolved in the file set
  double offset[3] = {0.0, 0.0, 0.0};
  double scale[3] = {1.0, 1.0, 1.0};
  bool clamp = false;
  double bump_multiplier = 1.0;
};

class MtlParser {
 public:
  MtlParser(std::string_view bytes, std::string_view name,
            std::vector<std::string>* notes)
      : name_(name), lines_(bytes), notes_(notes) {}

  Result<std::vector<MtlMaterial>> Parse() {
    std::string_view line;
    while (NextStatementLine(lines_, &line)) {
      TokenSplitter tokens(line);
      std::string_view keyword;
      if (!tokens.Next(&keyword)) continue;
      MW_RETURN_IF_ERROR(Statement(keyword, tokens));
    }
    if (!dropped_.empty()) {
      std::string list;
      for (const std::string& k : dropped_)
        list += (list.empty() ? "" : ", ") + k;
      notes_->push_back(std::string(name_) + ": " + list +
                        " not carried (MTL materials become metallic-"
                        "roughness ones: Kd, map_Kd, d/Tr, Ke/map_Ke, Pr/Pm "
                        "and bump/norm are read)");
    }
    return std::move(materials_);
  }

 private:
  Status Error(const std::string& what) const {
    return MeshParseError(name_, LineWhere(lines_.number()), what);
  }

  Result<Material*> Current(std::string_view keyword) {
    if (materials_.empty()) {
      return Error(std::string(keyword) + " before any newmtl");
    }
    return &materials_.back().material;
  }

  Status Numbers(TokenSplitter& tokens, std::string_view keyword, size_t min,
                 size_t max, double* out, size_t* count) {
    std::string_view token;
    *count = 0;
    while (tokens.Next(&token)) {
      if (*count == max) break;
      if (!ParseDouble(token, &out[*count]) || !FitsFloat(out[*count])) {
        return Error(std::string(keyword) + ": bad number " + Quoted(token) +
                     (token == "spectral" || token == "xyz"
                          ? " (only RGB colours are supported)"
                          : ""));
      }
      ++*count;
    }
    if (*count < min) {
      return Error(std::string(keyword) + " needs " + std::to_string(min) +
                   " number(s)");
    }
    return Status::Ok();
  }

  // A colour statement: "Kd r [g b]" (g and b default to r).
  Status Color(TokenSplitter& tokens, std::string_view keyword, float* rgb) {
    double v[3] = {0.0, 0.0, 0.0};
    size_t n = 0;
    MW_RETURN_IF_ERROR(Numbers(tokens, keyword, 1, 3, v, &n));
    if (n == 2) return Error(std::string(keyword) + " needs 1 or 3 numbers");
    if (n == 1) v[1] = v[2] = v[0];
    for (int k = 0; k < 3; ++k) rgb[k] = static_cast<float>(v[k]);
    return Status::Ok();
  }

  Result<TextureStatement> Texture(TokenSplitter& tokens,
                                   std::string_view keyword) {
    TextureStatement t;
    while (true) {
      TokenSplitter probe = tokens;
      std::string_view option;
      if (!probe.Next(&option)) {
        return Error(std::string(keyword) + " names no file");
      }
      if (option.size() < 2 || option[0] != '-' || IsNumber(option)) break;
      const int arity = OptionArity(option);
      if (arity < 0) {
        return Error(std::string(keyword) + ": unknown option " +
                     Quoted(option));
      }
      tokens = probe;
      std::string_view args[3];
      int taken = 0;
      for (; taken < arity; ++taken) {
        TokenSplitter look = tokens;
        std::string_view arg;
        if (!look.Next(&arg)) break;
        // -o, -s, -t take up to three numbers: stop at the first non-number.
        if (arity == 3 && taken > 0 && !IsNumber(arg)) break;
        args[taken] = arg;
        tokens = look;
      }
      if (taken == 0) {
        return Error(std::string(keyword) + ": option " + Quoted(option) +
                     " needs a value");
      }
      if (option == "-o" || option == "-s" || option == "-bm") {
        for (int k = 0; k < taken; ++k) {
          double v = 0.0;
          if (!ParseDouble(args[k], &v) || !FitsFloat(v)) {
            return Error(std::string(keyword) + ": option " + Quoted(option) +
                         " needs numbers, got " + Quoted(args[k]));
          }
          if (option == "-o") t.offset[k] = v;
          if (option == "-s") t.scale[k] = v;
          if (option == "-bm") t.bump_multiplier = v;
        }
      } else if (option == "-clamp") {
        t.clamp = args[0] == "on";
      }
    }
    std::string file(tokens.Rest());
    while (!file.empty() && IsSpace(file.back())) file.pop_back();
    std::replace(file.begin(), file.end(), '\\', '/');
    Result<std::string> resolved = ResolveFileSetReference(name_, file);
    if (!resolved.ok()) {
      return resolved.status().WithContext(std::string(name_) + ": " +
                                           LineWhere(lines_.number()));
    }
    t.file = std::move(resolved).value();
    return t;
  }

  // A slot's UV transform from -o/-s, in glTF's UV convention: with OBJ's
  // v' = s * v + o and v_gltf = 1 - v, v_gltf' = s * v_gltf + (1 - s - o).
  static TextureRef Slot(const TextureStatement& t) {
    TextureRef ref;
    ref.wrap_u = ref.wrap_v =
        t.clamp ? WrapMode::kClampToEdge : WrapMode::kRepeat;
    ref.transform << static_cast<float>(t.scale[0]), 0.0f,
        static_cast<float>(t.offset[0]), 0.0f, static_cast<float>(t.scale[1]),
        static_cast<float>(1.0 - t.scale[1] - t.offset[1]);
    return ref;
  }

  Status Statement(std::string_view keyword, TokenSplitter& tokens) {
    if (keyword == "newmtl") {
      std::string name(tokens.Rest());
      while (!name.empty() && IsSpace(name.back())) name.pop_back();
      if (name.empty()) return Error("newmtl needs a name");
      MtlMaterial m;
      m.material.name = std::move(name);
      m.material.metallic_factor = 0.0f;  // MTL materials are dielectric
      materials_.push_back(std::move(m));
      return Status::Ok();
    }
    if (keyword == "Kd") {
      MW_ASSIGN_OR_RETURN(Material * m, Current(keyword));
      return Color(tokens, keyword, m->base_color_factor.data());
    }
    if (keyword == "Ke") {
      MW_ASSIGN_OR_RETURN(Material * m, Current(keyword));
      return Color(tokens, keyword, m->emissive_factor.data());
    }
    if (keyword == "d" || keyword == "Tr" || keyword == "Pr" ||
        keyword == "Pm") {
      MW_ASSIGN_OR_RETURN(Material * m, Current(keyword));
      TokenSplitter probe = tokens;
      std::string_view first;
      if (keyword == "d" && probe.Next(&first) && first == "-halo")
        tokens = probe;
      double v = 0.0;
      size_t n = 0;
      MW_RETURN_IF_ERROR(Numbers(tokens, keyword, 1, 1, &v, &n));
      const float f = static_cast<float>(std::clamp(v, 0.0, 1.0));
      if (keyword == "Pr") {
        m->roughness_factor = f;
      } else if (keyword == "Pm") {
        m->metallic_factor = f;
      } else {
        // d wins over Tr when a file gives both (exporters write both).
        if (keyword == "d") have_d_.insert(materials_.size());
        if (keyword == "Tr" && have_d_.count(materials_.size()) != 0) {
          return Status::Ok();
        }
        m->base_color_factor[3] = keyword == "d" ? f : 1.0f - f;
        m->alpha_mode = m->base_color_factor[3] < 1.0f ? AlphaMode::kBlend
                                                       : AlphaMode::kOpaque;
      }
      return Status::Ok();
    }
    const bool base = keyword == "map_Kd";
    const bool normal = keyword == "map_Bump" || keyword == "map_bump" ||
                        keyword == "bump" || keyword == "norm" ||
                        keyword == "map_Norm";
    const bool emissive = keyword == "map_Ke";
    if (base || normal || emissive) {
      MW_ASSIGN_OR_RETURN(Material * m, Current(keyword));
      MW_ASSIGN_OR_RETURN(const TextureStatement t, Texture(tokens, keyword));
      MtlMaterial& entry = materials_.back();
      if (base) {
        m->base_color_texture = Slot(t);
        entry.base_color_file = t.file;
      } else if (normal) {
        m->normal_texture = Slot(t);
        m->normal_scale = static_cast<float>(t.bump_multiplier);
        entry.normal_file = t.file;
      } else {
        m->emissive_texture = Slot(t);
        entry.emissive_file = t.file;
        // MTL multiplies map_Ke by Ke, which defaults to black only when
        // absent; a texture alone means full emission.
        if (m->emissive_factor.isZero()) m->emissive_factor.setOnes();
      }
      return Status::Ok();
    }
    if (materials_.empty() && keyword != "newmtl") {
      return Error(std::string("statement ") + Quoted(keyword) +
                   " before any newmtl");
    }
    dropped_.insert(std::string(keyword.substr(0, 24)));
    return Status::Ok();
  }

  std::string_view name_;
  LineSplitter lines_;
  std::vector<std::string>* notes_;
  std::vector<MtlMaterial> materials_;
  std::set<size_t> have_d_;        // materials (1-based count) that had d
  std::set<std::string> dropped_;  // keywords not carried
};

}  // namespace

Result<std::vector<MtlMaterial>> ParseMtl(std::string_view bytes,
                                          std::string_view name,
                                          std::vector<std::string>* notes) {
  return MtlParser(bytes, name, notes).Parse();
}

}  // namespace meshwave
