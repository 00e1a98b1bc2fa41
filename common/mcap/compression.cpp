#include "common/mcap/compression.hpp"

#include <zstd.h>

namespace fsd::mcap {

const char* to_string(Compression c) { return c == Compression::Zstd ? "zstd" : ""; }

struct ZstdCompressor::Impl {
  ZSTD_CCtx* cctx = ZSTD_createCCtx();
};

struct ChunkDecompressor::Impl {
  ZSTD_DCtx* dctx = ZSTD_createDCtx();
};

ChunkDecompressor::ChunkDecompressor() : impl_(std::make_unique<Impl>()) {
  if (!impl_->dctx) throw McapError("zstd: cannot create a decompression context");
}

ChunkDecompressor::~ChunkDecompressor() { ZSTD_freeDCtx(impl_->dctx); }

ZstdCompressor::ZstdCompressor(int level) : impl_(std::make_unique<Impl>()) {
  if (!impl_->cctx) throw McapError("zstd: cannot create a compression context");
  ZSTD_CCtx_setParameter(impl_->cctx, ZSTD_c_compressionLevel, level);
  // The frame states its content size, so a reader can check it against the chunk's uncompressed_size.
  ZSTD_CCtx_setParameter(impl_->cctx, ZSTD_c_contentSizeFlag, 1);
}

ZstdCompressor::~ZstdCompressor() { ZSTD_freeCCtx(impl_->cctx); }

void ZstdCompressor::compress(std::span<const std::uint8_t> in, Bytes& out) {
  out.resize(ZSTD_compressBound(in.size()));
  const std::size_t n = ZSTD_compress2(impl_->cctx, out.data(), out.size(), in.data(), in.size());
  if (ZSTD_isError(n)) throw McapError(std::string("zstd compression failed: ") + ZSTD_getErrorName(n));
  out.resize(n);
}

std::string ChunkDecompressor::decompress(const std::string& compression, std::span<const std::uint8_t> in,
                                          std::uint64_t uncompressed_size, Bytes& out) {
  if (compression.empty()) {
    if (in.size() != uncompressed_size) return "uncompressed chunk whose size differs from its uncompressed_size";
    out.assign(in.begin(), in.end());
    return "";
  }
  if (compression != "zstd") return "compression '" + compression + "' is not supported (only none and zstd)";
  // A frame that states its size must state the chunk's: this rejects a lying size before allocating for it.
  const unsigned long long stated = ZSTD_getFrameContentSize(in.data(), in.size());
  if (stated == ZSTD_CONTENTSIZE_ERROR) return "damaged zstd data";
  if (stated != ZSTD_CONTENTSIZE_UNKNOWN && stated != uncompressed_size)
    return "zstd frame size differs from the chunk's uncompressed_size";
  out.resize(static_cast<std::size_t>(uncompressed_size));
  const std::size_t n = ZSTD_decompressDCtx(impl_->dctx, out.data(), out.size(), in.data(), in.size());
  if (ZSTD_isError(n)) return std::string("damaged zstd data (") + ZSTD_getErrorName(n) + ")";
  if (n != uncompressed_size) return "zstd data decompresses to another size than the chunk's uncompressed_size";
  return "";
}

}  // namespace fsd::mcap
