// The size an image file declares in its header, read without decoding it, so
// that a dataset image too large to decode is refused before the decoder
// allocates it (a header can declare any size: a few bytes can ask for
// gigabytes). Recognised: PNG (IHDR), JPEG (the SOFn frame header), and the
// PNM family (P1-P6: PBM, PGM, PPM), and BMP (the feature benchmarks' pairs
// may be BMP). Anything else is left to the decoder.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace duskmap {

// The most pixels a dataset image may have (64 Mpixels, far above any RGB-D
// camera); shared by the file readers and the database blob decoder.
inline constexpr int64_t kMaxImagePixels = int64_t{1} << 26;

struct ImageHeaderSize {
  int64_t width = 0;
  int64_t height = 0;
};

// True when width x height is at most kMaxImagePixels; sides are compared
// first, so that any declared size (PNG allows 2^31 - 1 per side) is judged
// without overflowing the product.
bool WithinPixelLimit(const ImageHeaderSize& size);

// The width and height declared by the header of a PNG, JPEG, PNM or BMP image in
// `data`; nullopt when the bytes are none of these, or the header is cut
// short or does not say (the decoder then judges the file itself).
std::optional<ImageHeaderSize> ReadImageHeaderSize(const uint8_t* data, size_t size);

// The same for a file; reads only the header (for JPEG, the marker segments
// before the frame header, skipping their payloads). nullopt also when the
// file cannot be opened.
std::optional<ImageHeaderSize> ReadImageFileHeaderSize(const std::string& path);

// Throws InputError "<path>: <w>x<h> image exceeds the 64-Mpixel limit" when
// the file's header declares more than kMaxImagePixels pixels, and "<path>:
// not a PNG, JPEG, PNM or BMP image ..." when the file (3 bytes or more) is another
// format; does nothing for smaller images and for files whose size the header
// does not give (missing, cut short: the decoder then refuses them).
void CheckImageFilePixelLimit(const std::string& path);

// How far from its end an encoded image is searched for its end marker:
// encoders may pad a JPEG after its end-of-image marker.
inline constexpr size_t kImageTrailerSearchBytes = 64;

// Why the last `tail_size` bytes of an encoded image (`tail`, at most
// kImageTrailerSearchBytes; the whole image when shorter) show it cut short:
// "JPEG is truncated (no end-of-image marker)" when no FF D9 marker lies
// there, "PNG is truncated (no IEND chunk)" when the PNG does not end with
// its IEND chunk; empty when the image ends as its format requires. A
// decoder given a cut JPEG returns a partly grey image without an error; PNM
// has no end marker (its decoder refuses a file shorter than its header says).
// `is_jpeg`/`is_png` say the format (from the first bytes).
std::string ImageTruncation(bool is_jpeg, bool is_png, const uint8_t* tail, size_t tail_size);

// Every check of an image file before it is decoded, in one call for the
// readers of dataset, texture and benchmark images: a path that is not a
// regular file is refused without opening it (a FIFO would block), then the
// format and the pixel limit (CheckImageFilePixelLimit), then truncation:
// "<path>: JPEG is truncated (no end-of-image marker)". A missing file is left
// to the decoder's caller, which names it.
void CheckImageFileBeforeDecoding(const std::string& path);

}  // namespace duskmap
