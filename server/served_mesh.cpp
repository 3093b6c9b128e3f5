#include "served_mesh.h"

#include <utility>

#include "meshwave/container.h"
#include "sha256.h"

namespace meshwave::server {

Result<std::shared_ptr<const ServedMesh>> ServedMesh::Load(
    CatalogEntry entry, const std::filesystem::path& file) {
  std::shared_ptr<ServedMesh> m(new ServedMesh());
  MW_ASSIGN_OR_RETURN(m->map_, MappedFile::Open(file));
  // A container damaged on disk (a flipped bit, a bad copy) is refused by
  // its content hash, which the row recorded at ingest, rather than served
  // as garbage: most damage lands in payloads, which parse fine.
  if (Sha256Hex(m->map_->bytes()) != entry.sha256) {
    return IoError(file.string() + ": SHA-256 differs from the catalog's (corrupt container)");
  }
  MW_ASSIGN_OR_RETURN(ParsedContainer parsed, ParseContainer(m->map_->bytes()));
  MW_RETURN_IF_ERROR(ValidateStreamHeader(parsed.header));
  const size_t count = parsed.header.packets.length.size();
  if (parsed.ids.size() != count) {
    return ParseError(file.string() + ": the container does not hold every packet");
  }
  m->payloads_.resize(count);
  for (size_t i = 0; i < parsed.ids.size(); ++i) {
    m->payloads_[parsed.ids[i]] = parsed.payloads[i];
    m->payload_bytes_ += parsed.payloads[i].size();
  }
  m->header_ = std::move(parsed.header);
  m->header_.present.clear();
  const int levels = static_cast<int>(m->levels());
  for (int max_level = -1; max_level <= levels; ++max_level) {
    for (Progression p : {Progression::kQuality, Progression::kResolution, Progression::kRd}) {
      m->orders_.push_back(PacketOrder(m->header_, p, max_level));
    }
  }
  const auto& quality = m->Order(Progression::kQuality, -1);
  const std::vector<double> psnr = EstimatedPsnrCurve(m->header_, quality);
  std::vector<uint32_t> prefix;
  for (size_t k = 0; k <= quality.size(); ++k) {
    m->rd_table_.push_back({static_cast<uint32_t>(k), ContainerSize(m->header_, prefix), psnr[k]});
    if (k < quality.size()) prefix.push_back(quality[k]);
  }
  m->entry_ = std::move(entry);
  return std::shared_ptr<const ServedMesh>(std::move(m));
}

Status ServedMesh::CheckLevelLimit(int max_level) const {
  if (max_level <= static_cast<int>(levels())) return Status::Ok();
  return InvalidArgument("max_level " + std::to_string(max_level) + " exceeds the " +
                         std::to_string(levels()) + " levels of mesh " + entry_.id);
}

const std::vector<uint32_t>& ServedMesh::Order(Progression p, int max_level) const {
  return orders_[3 * static_cast<size_t>(max_level + 1) + static_cast<size_t>(p)];
}

Result<const UnitTable*> ServedMesh::units() const {
  std::call_once(units_once_, [this] {
    auto table = UnitTable::Build(header_, payloads_);
    if (table.ok()) {
      units_ = std::move(*table);
    } else {
      units_status_ = ParseError("mesh " + entry_.id + ": " + table.status().message());
    }
  });
  if (!units_) return units_status_;
  return units_.get();
}

Result<const StreamScreenErrors*> ServedMesh::screen_errors() const {
  MW_ASSIGN_OR_RETURN(const UnitTable* table, units());
  std::call_once(screen_errors_once_, [this, table] {
    auto measured = StreamScreenErrors::Measure(header_, payloads_, table->precincts());
    if (measured.ok()) {
      screen_errors_ = std::make_unique<const StreamScreenErrors>(*std::move(measured));
    } else {
      screen_errors_status_ =
          ParseError("mesh " + entry_.id + ": " + measured.status().message());
    }
  });
  if (!screen_errors_) return screen_errors_status_;
  return screen_errors_.get();
}

}  // namespace meshwave::server
