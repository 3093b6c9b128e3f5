#!/bin/sh
# The decoder library holds no encoder code, and nothing of the file
# system, the input readers (meshes, assets, images), the request protocol
# or the server's region order: no symbol its objects define names one of
# them. The same patterns must find the encoders and the readers in the
# codec library, so that a pattern that matches nothing cannot pass
# unnoticed.
#   decoder_symbols_test.sh libmeshwave_decoder.a libmeshwave_codec.a
set -eu
decoder=$1
codec=$2
# Demangled names of the symbols an archive defines (text, data, weak).
defined() {
  nm -C --defined-only "$1" | sed -n 's/^[0-9a-f]* [TtWwVvDdBbRr] //p'
}
encoder='meshwave::(.*::)?(Encode[A-Z][A-Za-z]*|[A-Za-z]*Encoder[A-Za-z]*|TraverseBaseMesh|ChooseTransmissionOrder|WaveletTransform::Forward)\b'
beyond='meshwave::(.*::)?(WriteFileDurably|Parse(Sphere|View)Region|ParseScreenError|FormatRegionShape|DecodeHeldUnits|UnitRecordReader|RegionOrder|StreamPrecincts|(Parse|Read)MeshAsset|ReadMesh|Decode(Image|Png|Jpeg|Webp))\b|tinygltf::'
status=0
found=$(defined "$decoder" | grep -E "$encoder|$beyond" | sort -u || true)
if [ -n "$found" ]; then
  echo "FAIL: $decoder defines encoder, file-system, asset, protocol or server symbols:"
  echo "$found"
  status=1
fi
if ! defined "$decoder" | grep -q 'meshwave::ProgressiveDecoder::AddPacket('; then
  echo "FAIL: $decoder does not define ProgressiveDecoder::AddPacket (wrong archive?)"
  status=1
fi
for name in 'meshwave::ArithmeticEncoder::Finish' 'meshwave::TraverseBaseMesh' \
            'meshwave::EncodeBaseMesh' 'meshwave::EncodeSawtChoices' \
            'meshwave::EncodeBaseRefinementPlane' 'meshwave::WaveletTransform::Forward'; do
  if ! defined "$codec" | grep -E "$encoder" | grep -qF "$name"; then
    echo "FAIL: the encoder pattern does not find $name in $codec"
    status=1
  fi
done
for name in 'meshwave::ReadMeshAsset' 'meshwave::ReadMesh'; do
  if ! defined "$codec" | grep -E "$beyond" | grep -qF "$name("; then
    echo "FAIL: the pattern of what lies beyond the decoder does not find $name in $codec"
    status=1
  fi
done
[ $status -eq 0 ] && echo "ok: $(defined "$decoder" | wc -l) symbols of the decoder, none of the encoder"
exit $status
