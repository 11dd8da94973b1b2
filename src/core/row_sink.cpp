#include "core/row_sink.hpp"

#include <algorithm>
#include <stdexcept>

namespace stiction::core {

DecimatedTrajectory::DecimatedTrajectory(std::vector<std::string> columns, std::size_t capacity,
                                         std::size_t min_stride)
    : trajectory_(std::move(columns)),
      capacity_(std::max<std::size_t>(capacity, 4)),
      stride_(std::max<std::size_t>(min_stride, 1)) {
  // Room for every row it can hold at once when that is a few MB (the plots' copy, 16384
  // rows): appending then never reallocates, and thinning works in place. Pages are touched
  // only as rows arrive.
  trajectory_.reserve_rows(static_cast<int>(std::min<std::size_t>(capacity_ + 1, 16385)));
}

void DecimatedTrajectory::write(const double* rows, std::size_t count, std::size_t columns) {
  if (columns != static_cast<std::size_t>(trajectory_.column_count())) {
    throw std::logic_error("DecimatedTrajectory: rows of another width");
  }
  for (std::size_t r = 0; r < count; ++r, ++seen_) {
    const double* row = rows + r * columns;
    last_kept_ = seen_ % stride_ == 0;
    if (last_kept_) {
      if (static_cast<std::size_t>(trajectory_.row_count()) >= capacity_) thin();
      // After thinning the stride doubled: this row may no longer be on it.
      last_kept_ = seen_ % stride_ == 0;
      if (last_kept_) trajectory_.append(row);
    }
    if (r + 1 == count) last_.assign(row, row + columns);
  }
}

void DecimatedTrajectory::thin() {
  // Kept rows are those with index % stride == 0; keep those with index % (2 stride) == 0,
  // which are the even positions of the table.
  trajectory_.keep_even_rows();
  stride_ *= 2;
}

void DecimatedTrajectory::finish() {
  if (!last_kept_ && !last_.empty()) trajectory_.append(last_.data());
  last_kept_ = true;
}

}  // namespace stiction::core
