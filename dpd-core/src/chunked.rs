//! Order-preserving parallel flat map, used to build pair lists on all threads with the
//! same result as one thread.

use rayon::prelude::*;

/// Below this many items the work is not split across threads.
const PARALLEL_MIN_ITEMS: usize = 64;

/// Apply `f` to every item, each appending its outputs to a buffer; return all outputs in item
/// order and the number each item produced. The result does not depend on the thread count:
/// chunks are fixed by the item count alone and concatenated in order.
pub(crate) fn flat_map_ordered<T: Sync, U: Send>(
    items: &[T],
    f: impl Fn(&T, &mut Vec<U>) + Sync,
) -> (Vec<U>, Vec<u32>) {
    let run = |chunk: &[T]| {
        let mut out = Vec::new();
        let lens = chunk
            .iter()
            .map(|item| {
                let before = out.len();
                f(item, &mut out);
                (out.len() - before) as u32
            })
            .collect::<Vec<u32>>();
        (out, lens)
    };
    if items.len() < PARALLEL_MIN_ITEMS || rayon::current_num_threads() == 1 {
        return run(items);
    }
    let chunk = items.len().div_ceil(64).max(16);
    let parts: Vec<(Vec<U>, Vec<u32>)> = items.par_chunks(chunk).map(run).collect();
    let total = parts.iter().map(|(out, _)| out.len()).sum();
    let mut out = Vec::with_capacity(total);
    let mut lens = Vec::with_capacity(items.len());
    for (o, l) in parts {
        out.extend(o);
        lens.extend(l);
    }
    (out, lens)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_result_on_any_thread_count() {
        let items: Vec<u32> = (0..1000).collect();
        let f = |&k: &u32, out: &mut Vec<u32>| out.extend((0..k % 7).map(|x| x * k));
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        let three = rayon::ThreadPoolBuilder::new()
            .num_threads(3)
            .build()
            .unwrap();
        let a = one.install(|| flat_map_ordered(&items, f));
        let b = three.install(|| flat_map_ordered(&items, f));
        assert_eq!(a, b);
        assert_eq!(a.1.len(), items.len());
        assert_eq!(a.1.iter().sum::<u32>() as usize, a.0.len());
    }
}
