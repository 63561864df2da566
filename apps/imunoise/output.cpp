#include "output.hpp"

#include "imunoise/io/atomic_output.hpp"

namespace imunoise::cli {

void write_output(const OutputOptions& options, const std::string& text) {
  io::AtomicOutput out(options.path, options.force);
  out.write(text.data(), text.size());
  out.commit();
}

}  // namespace imunoise::cli
