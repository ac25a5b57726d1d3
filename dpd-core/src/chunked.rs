//! Order-preserving parallel flat map into reusable parts, used to build pair lists on all
//! threads with the same result as one thread.

use crate::parallel::each_in_parallel;
use std::ops::Range;

/// A sequence stored as consecutive parts, one per chunk of the work that produced it, so that
/// threads fill their parts in place and nothing is copied to join them. The parts keep their
/// allocations between fills.
#[derive(Clone, Debug)]
pub struct Parts<U> {
    parts: Vec<Vec<U>>,
    /// `starts[k]`: index of the first item of part `k` in the whole sequence; one more entry
    /// holds the length.
    starts: Vec<usize>,
}

impl<U> Default for Parts<U> {
    fn default() -> Self {
        Parts {
            parts: Vec::new(),
            starts: vec![0],
        }
    }
}

impl<U> Parts<U> {
    /// Number of items.
    pub fn len(&self) -> usize {
        *self.starts.last().unwrap_or(&0)
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// All items in order.
    pub fn iter(&self) -> impl DoubleEndedIterator<Item = &U> + '_ {
        self.parts.iter().flatten()
    }

    /// Items `range` of the sequence, which must lie within one part (a range produced by one
    /// work item always does).
    #[inline]
    pub fn slice(&self, range: Range<usize>) -> &[U] {
        let k = self.starts.partition_point(|&s| s <= range.start) - 1;
        let k = k.min(self.parts.len().saturating_sub(1));
        let s = self.starts[k];
        self.parts
            .get(k)
            .map_or(&[], |p| &p[range.start - s..range.end - s])
    }
}

impl<U> Parts<U> {
    /// Append one more part, filled by `f`.
    pub(crate) fn append(&mut self, f: impl FnOnce(&mut Vec<U>)) {
        let mut part = Vec::new();
        f(&mut part);
        let total = self.len() + part.len();
        self.parts.push(part);
        self.starts.push(total);
    }
}

/// Apply `f` to every item, each appending its outputs to a buffer; refill `out` with all
/// outputs in item order and return the number each item produced. `groups` splits the items
/// into consecutive groups, `groups[g]..groups[g + 1]` (from 0 to `items.len()`): a group's
/// items are processed after every item of the groups before it. When `parallel` and the pool
/// has more than one thread, each of the first `split` groups is split into up to 32 chunks of
/// consecutive items, filled on all threads (the rest are filled in order on one thread); the
/// result does not depend on the thread count, since the parts are read in order.
pub(crate) fn flat_map_ordered<T: Sync, U: Send>(
    items: &[T],
    groups: &[u32],
    split: usize,
    out: &mut Parts<U>,
    parallel: bool,
    f: impl Fn(&T, &mut Vec<U>) + Sync,
) -> Vec<u32> {
    debug_assert!(groups.first() == Some(&0) && groups.last() == Some(&(items.len() as u32)));
    let threads = parallel && rayon::current_num_threads() > 1;
    // Chunks as item ranges, group by group, and where each group's chunks start.
    let (mut chunks, mut group_chunks) = (Vec::new(), vec![0]);
    for (k, g) in groups.windows(2).enumerate() {
        let (start, end) = (g[0] as usize, g[1] as usize);
        let len = if threads && k < split {
            (end - start).div_ceil(32).max(1)
        } else {
            (end - start).max(1)
        };
        chunks.extend((start..end).step_by(len).map(|k| k..(k + len).min(end)));
        group_chunks.push(chunks.len());
    }
    out.parts.resize_with(chunks.len(), Vec::new);
    out.parts.truncate(chunks.len());
    let run = |chunk: &[T], part: &mut Vec<U>| {
        // Room for the previous fill and 3 % more, so that a part seldom grows.
        let previous = part.len();
        part.clear();
        part.reserve(previous + previous / 32);
        let lens = chunk
            .iter()
            .map(|item| {
                let before = part.len();
                f(item, part);
                (part.len() - before) as u32
            })
            .collect::<Vec<u32>>();
        // A part that grew by doubling gives the excess back.
        let n = part.len();
        if part.capacity() > n + n / 16 + 64 {
            part.shrink_to(n + n / 32);
        }
        lens
    };
    let mut lens: Vec<Vec<u32>> = Vec::with_capacity(chunks.len());
    let mut parts = &mut out.parts[..];
    for g in group_chunks.windows(2) {
        let (ranges, rest) = (&chunks[g[0]..g[1]], std::mem::take(&mut parts));
        let (mine, rest) = rest.split_at_mut(ranges.len());
        parts = rest;
        if ranges.len() > 1 {
            let mut part_lens = vec![Vec::new(); ranges.len()];
            each_in_parallel(mine, &mut part_lens, &|k, part, part_lens| {
                *part_lens = run(&items[ranges[k].clone()], part);
            });
            lens.extend(part_lens);
        } else {
            let parts = ranges.iter().zip(mine.iter_mut());
            lens.extend(parts.map(|(r, part)| run(&items[r.clone()], part)));
        }
    }
    out.starts.clear();
    out.starts.push(0);
    let mut total = 0;
    for part in &out.parts {
        total += part.len();
        out.starts.push(total);
    }
    lens.concat()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_result_on_any_thread_count() {
        let items: Vec<u32> = (0..1000).collect();
        let groups = [0, 1, 400, 401, 1000];
        let f = |&k: &u32, out: &mut Vec<u32>| out.extend((0..k % 7).map(|x| x * k));
        let (mut out_a, mut out_b) = (Parts::default(), Parts::default());
        let a = crate::on_threads(1, || {
            flat_map_ordered(&items, &groups, 3, &mut out_a, true, f)
        });
        let b = crate::on_threads(3, || {
            // A second fill reuses the parts.
            flat_map_ordered(&items[..10], &[0, 3, 10], 2, &mut out_b, true, f);
            flat_map_ordered(&items, &groups, 3, &mut out_b, true, f)
        });
        assert_eq!(a, b);
        let (all_a, all_b): (Vec<u32>, Vec<u32>) = (
            out_a.iter().copied().collect(),
            out_b.iter().copied().collect(),
        );
        assert_eq!(all_a, all_b);
        assert_eq!(a.len(), items.len());
        assert_eq!(a.iter().sum::<u32>() as usize, out_a.len());
        // Every item's output is one slice.
        let mut start = 0;
        for (item, &n) in items.iter().zip(&a) {
            let end = start + n as usize;
            let want: Vec<u32> = (0..item % 7).map(|x| x * item).collect();
            assert_eq!(out_b.slice(start..end), &want[..]);
            start = end;
        }
    }
}
