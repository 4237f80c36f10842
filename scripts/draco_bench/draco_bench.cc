// Same-run Draco baseline for lrmesh's Edgebreaker decode (not part of CI; see
// scripts/draco-compare.sh). For one .drc file, prints one line of key=value pairs:
// faces, conn_bytes (the bytes before the attribute data: header and connectivity), conn_bpt,
// conn_mtps (median M triangles/s of a decode that stops after the connectivity: attribute
// decoding is skipped) and full_mtps (median M triangles/s of the whole decode).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <memory>
#include <vector>

#include "draco/compression/decode.h"
#include "draco/compression/mesh/mesh_edgebreaker_decoder.h"

namespace {

// Edgebreaker decoder that decodes the connectivity only, and records how many bytes the
// connectivity took.
class ConnectivityOnly : public draco::MeshEdgebreakerDecoder {
 public:
  // Input size; the connectivity decoder repositions the buffer, so what it consumed is
  // measured as what is left for the attributes.
  int64_t total = 0;
  int64_t conn_bytes = 0;

 protected:
  bool DecodeConnectivity() override {
    const bool ok = draco::MeshEdgebreakerDecoder::DecodeConnectivity();
    conn_bytes = total - buffer()->remaining_size();
    return ok;
  }
  bool DecodePointAttributes() override { return true; }
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char **argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s FILE.drc [RUNS]\n", argv[0]);
    return 2;
  }
  const int runs = argc > 2 ? std::atoi(argv[2]) : 21;
  std::ifstream in(argv[1], std::ios::binary);
  std::vector<char> data((std::istreambuf_iterator<char>(in)),
                         std::istreambuf_iterator<char>());
  if (data.empty()) {
    std::fprintf(stderr, "cannot read %s\n", argv[1]);
    return 1;
  }
  using clock = std::chrono::steady_clock;
  std::vector<double> conn, full;
  int64_t faces = 0, conn_bytes = 0;
  for (int i = 0; i < runs; ++i) {
    {
      draco::DecoderBuffer buf;
      buf.Init(data.data(), data.size());
      draco::DecoderOptions options;
      draco::Mesh mesh;
      ConnectivityOnly dec;
      dec.total = static_cast<int64_t>(data.size());
      const auto t0 = clock::now();
      const draco::Status s = dec.Decode(options, &buf, &mesh);
      const auto t1 = clock::now();
      if (!s.ok()) {
        std::fprintf(stderr, "draco connectivity decode failed: %s\n",
                     s.error_msg());
        return 1;
      }
      faces = mesh.num_faces();
      conn_bytes = dec.conn_bytes;
      conn.push_back(std::chrono::duration<double>(t1 - t0).count());
    }
    {
      draco::DecoderBuffer buf;
      buf.Init(data.data(), data.size());
      draco::Decoder dec;
      const auto t0 = clock::now();
      auto mesh = dec.DecodeMeshFromBuffer(&buf);
      const auto t1 = clock::now();
      if (!mesh.ok() || mesh.value()->num_faces() != faces) {
        std::fprintf(stderr, "draco full decode failed\n");
        return 1;
      }
      full.push_back(std::chrono::duration<double>(t1 - t0).count());
    }
  }
  std::printf("faces=%lld conn_bytes=%lld conn_bpt=%.3f conn_mtps=%.1f full_mtps=%.1f\n",
              (long long)faces, (long long)conn_bytes,
              8.0 * conn_bytes / faces, faces / median(conn) / 1e6,
              faces / median(full) / 1e6);
  return 0;
}
