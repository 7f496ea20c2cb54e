//! Data parallelism for the CPU twins and the reference: rayon's parallel iterators with the
//! `parallel` feature, and the same calls on the calling thread without it (a browser, or an
//! application that keeps its own threads). Every user of the crate writes
//! `use crate::parallel::prelude::*;`, so a twin reads the same either way and gives the same
//! result: each `fold` below is a per-worker partial sum, which the serial form makes once.

/// The traits and methods a module needs: rayon's prelude, or the serial stand-ins.
pub mod prelude {
    #[cfg(feature = "parallel")]
    pub use rayon::prelude::*;

    #[cfg(not(feature = "parallel"))]
    pub use super::serial::{IntoParallelIterator, ParallelSlice, ParallelSliceMut};
}

/// How many workers a parallel loop gets: rayon's pool, or the one calling thread.
pub fn workers() -> usize {
    #[cfg(feature = "parallel")]
    return rayon::current_num_threads();
    #[cfg(not(feature = "parallel"))]
    return 1;
}

/// `add(sums, i)` for every `i` in `range` into `len` sums: a partial sum per worker, then their
/// total (the CPU twins' scatter of light into a map).
pub fn par_sum(
    range: std::ops::Range<usize>,
    len: usize,
    add: impl Fn(&mut [glam::DVec3], usize) + Sync + Send,
) -> Vec<glam::DVec3> {
    use prelude::*;
    let zero = || vec![glam::DVec3::ZERO; len];
    range
        .into_par_iter()
        .fold(zero, |mut sums, i| {
            add(&mut sums, i);
            sums
        })
        .reduce(zero, |mut a, b| {
            a.iter_mut().zip(&b).for_each(|(x, y)| *x += *y);
            a
        })
}

/// rayon's iterator methods that this crate uses, on the calling thread. Where rayon's signature
/// differs from `Iterator`'s (`fold` takes an identity closure and yields partial results,
/// `reduce` one too), these follow rayon's.
#[cfg(any(test, not(feature = "parallel")))]
mod serial {
    use std::iter::{Enumerate, FlatMap, Map, Once};
    use std::slice::{ChunksMut, Iter};

    /// A sequential iterator that answers to rayon's method names.
    pub struct Serial<I>(I);

    /// `into_par_iter` on anything iterable.
    pub trait IntoParallelIterator: IntoIterator + Sized {
        /// The same items, in order, on this thread.
        fn into_par_iter(self) -> Serial<Self::IntoIter> {
            Serial(self.into_iter())
        }
    }
    impl<I: IntoIterator> IntoParallelIterator for I {}

    /// `par_iter` on slices.
    pub trait ParallelSlice<T> {
        /// The slice's items, in order.
        fn par_iter(&self) -> Serial<Iter<'_, T>>;
    }
    impl<T> ParallelSlice<T> for [T] {
        fn par_iter(&self) -> Serial<Iter<'_, T>> {
            Serial(self.iter())
        }
    }

    /// `par_chunks_mut` on slices.
    pub trait ParallelSliceMut<T> {
        /// The slice in mutable runs of `n`, in order.
        fn par_chunks_mut(&mut self, n: usize) -> Serial<ChunksMut<'_, T>>;
    }
    impl<T> ParallelSliceMut<T> for [T] {
        fn par_chunks_mut(&mut self, n: usize) -> Serial<ChunksMut<'_, T>> {
            Serial(self.chunks_mut(n))
        }
    }

    impl<I: Iterator> Serial<I> {
        /// rayon's `map`.
        pub fn map<B, F: FnMut(I::Item) -> B>(self, f: F) -> Serial<Map<I, F>> {
            Serial(self.0.map(f))
        }

        /// rayon's `enumerate`.
        pub fn enumerate(self) -> Serial<Enumerate<I>> {
            Serial(self.0.enumerate())
        }

        /// rayon's `flat_map_iter`.
        pub fn flat_map_iter<U: IntoIterator, F: FnMut(I::Item) -> U>(
            self,
            f: F,
        ) -> Serial<FlatMap<I, U, F>> {
            Serial(self.0.flat_map(f))
        }

        /// rayon's `fold`: one partial result, as from a single worker.
        pub fn fold<T, Id: Fn() -> T, F: FnMut(T, I::Item) -> T>(
            self,
            identity: Id,
            f: F,
        ) -> Serial<Once<T>> {
            Serial(std::iter::once(self.0.fold(identity(), f)))
        }

        /// rayon's `reduce`: `identity()` for no items.
        pub fn reduce<Id: Fn() -> I::Item, F: FnMut(I::Item, I::Item) -> I::Item>(
            self,
            identity: Id,
            f: F,
        ) -> I::Item {
            self.0.reduce(f).unwrap_or_else(identity)
        }

        /// rayon's `for_each`.
        pub fn for_each<F: FnMut(I::Item)>(self, f: F) {
            self.0.for_each(f)
        }

        /// rayon's `collect`.
        pub fn collect<C: FromIterator<I::Item>>(self) -> C {
            self.0.collect()
        }

        /// rayon's `unzip`.
        pub fn unzip<A, B, FromA, FromB>(self) -> (FromA, FromB)
        where
            I: Iterator<Item = (A, B)>,
            FromA: Default + Extend<A>,
            FromB: Default + Extend<B>,
        {
            self.0.unzip()
        }
    }
}

/// Runs `f` with every parallel loop in it on one thread, so that sums run in one order (the
/// tests that compare two runs bit for bit).
#[cfg(test)]
pub(crate) fn on_one_thread<R: Send>(f: impl FnOnce() -> R + Send) -> R {
    #[cfg(feature = "parallel")]
    return rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a one-thread pool")
        .install(f);
    #[cfg(not(feature = "parallel"))]
    return f();
}

#[cfg(test)]
mod tests {
    use super::serial::{IntoParallelIterator, ParallelSlice, ParallelSliceMut};

    /// The serial stand-ins give what rayon's calls give: the same items in the same order, one
    /// partial per `fold`, `reduce` over the partials.
    #[test]
    fn the_serial_stand_ins_answer_as_rayon_does() {
        let total = (1..=100u64)
            .into_par_iter()
            .fold(|| 0, |a, k| a + k)
            .reduce(|| 0, |a, b| a + b);
        assert_eq!(total, 5050);
        let empty = (0..0u64)
            .into_par_iter()
            .map(|k| k)
            .reduce(|| 7, |a, b| a + b);
        assert_eq!(empty, 7);

        let values: Vec<u32> = (0..10).collect();
        let doubled: Vec<u32> = values.par_iter().map(|v| 2 * v).collect();
        assert_eq!(doubled, (0..10).map(|v| 2 * v).collect::<Vec<_>>());
        let sums = super::par_sum(0..5, 2, |s, i| s[i % 2] += glam::DVec3::splat(i as f64));
        assert_eq!(sums, vec![glam::DVec3::splat(6.0), glam::DVec3::splat(4.0)]);
        let pairs: Vec<u32> = (0..3u32)
            .into_par_iter()
            .flat_map_iter(|i| (0..2).map(move |j| 10 * i + j))
            .collect();
        assert_eq!(pairs, vec![0, 1, 10, 11, 20, 21]);
        let (even, odd): (Vec<u32>, Vec<u32>) = (0..4u32)
            .into_par_iter()
            .map(|k| (2 * k, 2 * k + 1))
            .unzip();
        assert_eq!((even, odd), (vec![0, 2, 4, 6], vec![1, 3, 5, 7]));

        let mut rows = vec![0u32; 6];
        rows.par_chunks_mut(2)
            .enumerate()
            .for_each(|(i, row)| row.fill(i as u32));
        assert_eq!(rows, vec![0, 0, 1, 1, 2, 2]);
    }
}
