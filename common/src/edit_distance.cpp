#include "simpartner/edit_distance.h"

#include <algorithm>
#include <cctype>
#include <vector>

namespace simpartner {

size_t EditDistance(const std::string& a, const std::string& b) {
  auto same = [](char x, char y) {
    return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
  };
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same(a[i - 1], b[j - 1]) ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

}  // namespace simpartner

namespace simpartner {

std::string NearestName(const std::string& word, const std::vector<std::string>& candidates) {
  const size_t limit = std::max<size_t>(1, std::min<size_t>(3, word.size() / 2));
  std::string nearest;
  size_t best = 2 * limit + 2;  // score: twice the distance, one less for a name word begins
  for (const std::string& candidate : candidates) {
    const size_t d = EditDistance(word, candidate);
    if (d > limit) continue;
    const bool extends =
        candidate.size() > word.size() && EditDistance(word, candidate.substr(0, word.size())) == 0;
    const size_t score = 2 * d - (extends ? 1 : 0);
    if (score < best) {
      best = score;
      nearest = candidate;
    }
  }
  return nearest;
}

}  // namespace simpartner
