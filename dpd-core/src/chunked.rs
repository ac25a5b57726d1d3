//! Order-preserving parallel flat map, used to build pair lists on all threads with the
//! same result as one thread.

use rayon::prelude::*;

/// Below this many items the work is not split across threads.
const PARALLEL_MIN_ITEMS: usize = 64;

/// Apply `f` to every item, each appending its outputs to a buffer; refill `out` with all
/// outputs in item order (reusing its allocation) and return the number each item produced.
/// The result does not depend on the thread count: chunks are fixed by the item count alone
/// and concatenated in order.
pub(crate) fn flat_map_ordered<T: Sync, U: Send>(
    items: &[T],
    out: &mut Vec<U>,
    f: impl Fn(&T, &mut Vec<U>) + Sync,
) -> Vec<u32> {
    let run = |chunk: &[T], out: &mut Vec<U>| {
        chunk
            .iter()
            .map(|item| {
                let before = out.len();
                f(item, out);
                (out.len() - before) as u32
            })
            .collect::<Vec<u32>>()
    };
    let expected = out.len();
    out.clear();
    if items.len() < PARALLEL_MIN_ITEMS || rayon::current_num_threads() == 1 {
        return run(items, out);
    }
    let chunk = items.len().div_ceil(64).max(16);
    // Each chunk starts with room for its share of the previous total, plus a margin.
    let room = expected / items.len().div_ceil(chunk) * 9 / 8;
    let parts: Vec<(Vec<U>, Vec<u32>)> = items
        .par_chunks(chunk)
        .map(|c| {
            let mut part = Vec::with_capacity(room);
            let lens = run(c, &mut part);
            (part, lens)
        })
        .collect();
    let mut lens = Vec::with_capacity(items.len());
    for (part, l) in parts {
        out.extend(part);
        lens.extend(l);
    }
    lens
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
        let (mut out_a, mut out_b) = (Vec::new(), vec![7, 7]);
        let a = one.install(|| flat_map_ordered(&items, &mut out_a, f));
        let b = three.install(|| flat_map_ordered(&items, &mut out_b, f));
        assert_eq!((a.clone(), out_a.clone()), (b, out_b));
        assert_eq!(a.len(), items.len());
        assert_eq!(a.iter().sum::<u32>() as usize, out_a.len());
    }
}
