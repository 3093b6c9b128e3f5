#include "complete_stream.h"

#include "cli_util.h"

namespace meshwave::cli {

Status CompleteStream::Send(ProgressiveDecoder& d, const StreamUnit& u) const {
  if (u.whole()) return d.AddPacket(u.id, payload[u.id]);
  MW_ASSIGN_OR_RETURN(std::vector<std::string_view> parts,
                      PacketParts(*units, u.id, payload[u.id]));
  return d.AddPacketPart(u.id, u.part, parts[u.part]);
}

Result<std::unique_ptr<CompleteStream>> LoadCompleteStream(
    const std::string& path, const std::string& command) {
  auto s = std::make_unique<CompleteStream>();
  MW_ASSIGN_OR_RETURN(s->bytes, ReadFileBytes(path));
  MW_ASSIGN_OR_RETURN(s->container, ParseContainer(s->bytes));
  const StreamHeader& h = s->container.header;
  if (s->container.ids.size() != h.packets.length.size()) {
    return InvalidArgument(
        path + ": holds " + std::to_string(s->container.ids.size()) + " of " +
        std::to_string(h.packets.length.size()) + " packets; " + command +
        " needs the complete stream");
  }
  s->payload.resize(h.packets.length.size());
  for (size_t i = 0; i < s->container.ids.size(); ++i) {
    s->payload[s->container.ids[i]] = s->container.payloads[i];
  }
  MW_ASSIGN_OR_RETURN(StreamPrecincts precincts, StreamPrecincts::Create(h));
  s->precincts = std::make_unique<StreamPrecincts>(std::move(precincts));
  s->units = std::make_unique<HeldUnits>(h, s->precincts->parents());
  for (uint32_t id = 0; id < s->payload.size(); ++id) {
    MW_ASSIGN_OR_RETURN(std::vector<uint32_t> lengths,
                        PartLengths(*s->units, id, s->payload[id]));
    s->part_lengths.push_back(std::move(lengths));
  }
  MW_ASSIGN_OR_RETURN(auto decoder, ProgressiveDecoder::Create(h));
  for (uint32_t id = 0; id < s->payload.size(); ++id) {
    MW_RETURN_IF_ERROR(decoder->AddPacket(id, s->payload[id]));
  }
  s->full = decoder->Positions();
  s->faces = decoder->Faces();
  s->diagonal = HeaderDiagonal(h);
  return s;
}

}  // namespace meshwave::cli
