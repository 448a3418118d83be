// "Did you mean ...?" for misspelt names in scenes and on the command line.
#pragma once

#include <string>
#include <vector>

namespace uampc {

// The candidate closest to `word` by edit distance, or empty if none is close (more than a third
// of the word would have to change).
std::string closestMatch(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace uampc
