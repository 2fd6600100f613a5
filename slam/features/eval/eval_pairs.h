// Which pairs `duskmap features eval` scores (`--pairs`, `--pairs-file`): a
// list of selectors, each kept with where it came from so that an unknown
// or malformed one is named with its origin. A homography or static
// sequence reads them as image pairs "<i>-<j>" or "<sequence>/<i>-<j>"
// (image_sequence.h); the WxBS layout as pair names (epipolar_eval.h).
#pragma once

#include <string>
#include <vector>

namespace duskmap {

struct PairSelector {
  std::string text;    // "1-5", "notredame/1-6", "WGALBS/kremlin"
  std::string origin;  // "--pairs", or "<list file>:<line>"
};

// "1-5,1-6": one selector per comma-separated item (spaces around items
// ignored). ConfigError on a line break (`--pairs "$(cat list)"`: the
// message would quote it over two lines), an empty item or a selector listed
// twice.
std::vector<PairSelector> ParsePairList(const std::string& list);

// A list file: one or more comma-separated selectors per line; blank lines
// and text after '#' are ignored. InputError naming the file when it cannot
// be read or lists nothing; ConfigError naming file and line for a selector
// listed twice.
std::vector<PairSelector> ReadPairListFile(const std::string& path);

// The list file's parsing, on its text (what ReadPairListFile calls once it
// has read `path`): the same selectors and errors, origins "<path>:<line>".
std::vector<PairSelector> ParsePairListText(const std::string& text, const std::string& path);

// An image pair of a sequence: "<i>-<j>" or "<sequence>/<i>-<j>", i and j
// positive image indices (imgN's N), i != j.
struct ImagePairSelector {
  std::string sequence;  // empty: the pair in every sequence
  int first_index = 0;
  int second_index = 0;
};

// ConfigError "<origin>: '<text>' is not an image pair <i>-<j> or <sequence>/<i>-<j>".
ImagePairSelector ParseImagePairSelector(const PairSelector& selector);

}  // namespace duskmap
