//! Lists of lists stored flat (compressed rows).

use std::ops::Index;

/// A list of rows of indices stored in one vector with row offsets (compressed sparse
/// rows). A graph of a large model keeps its rows next to each other, in one
/// allocation, instead of one heap block per row.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Rows {
    /// Row `i` is `items[offsets[i]..offsets[i + 1]]`.
    offsets: Vec<usize>,
    items: Vec<usize>,
}

impl Default for Rows {
    fn default() -> Self {
        Rows::new()
    }
}

impl Rows {
    /// No rows.
    pub fn new() -> Self {
        Rows::with_capacity(0, 0)
    }

    /// No rows, with room for `rows` rows of `items` entries in all.
    pub fn with_capacity(rows: usize, items: usize) -> Self {
        let mut offsets = Vec::with_capacity(rows + 1);
        offsets.push(0);
        Rows {
            offsets,
            items: Vec::with_capacity(items),
        }
    }

    /// `n_rows` rows filled from `(row, item)` pairs, each row's items in the order the
    /// pairs come (a counting sort: `pairs` is called twice, to count and to fill, so
    /// no vector per row and no list of pairs is made).
    pub fn grouped<I: Iterator<Item = (usize, usize)>>(
        n_rows: usize,
        pairs: impl Fn() -> I,
    ) -> Self {
        let mut offsets = vec![0usize; n_rows + 1];
        for (r, _) in pairs() {
            offsets[r + 1] += 1;
        }
        for r in 0..n_rows {
            offsets[r + 1] += offsets[r];
        }
        let mut fill = offsets.clone();
        let mut items = vec![0usize; offsets[n_rows]];
        for (r, x) in pairs() {
            items[fill[r]] = x;
            fill[r] += 1;
        }
        Rows { offsets, items }
    }

    /// Total number of entries of all rows.
    pub fn n_items(&self) -> usize {
        self.items.len()
    }

    /// Appends a row.
    pub fn push(&mut self, row: &[usize]) {
        self.items.extend_from_slice(row);
        self.offsets.push(self.items.len());
    }

    /// Removes the last row.
    pub fn pop(&mut self) {
        if self.offsets.len() > 1 {
            self.offsets.pop();
            self.items
                .truncate(*self.offsets.last().expect("offset 0 stays"));
        }
    }

    /// Number of rows.
    pub fn len(&self) -> usize {
        self.offsets.len() - 1
    }

    /// Whether there is no row.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The rows in order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = &[usize]> + '_ {
        self.offsets.windows(2).map(|w| &self.items[w[0]..w[1]])
    }

    /// The rows as nested vectors (for tests and messages).
    pub fn to_vecs(&self) -> Vec<Vec<usize>> {
        self.iter().map(<[usize]>::to_vec).collect()
    }
}

impl Index<usize> for Rows {
    type Output = [usize];

    #[inline]
    fn index(&self, i: usize) -> &[usize] {
        &self.items[self.offsets[i]..self.offsets[i + 1]]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_push_pop_and_read_back() {
        let mut r = Rows::new();
        assert!(r.is_empty());
        r.push(&[3, 1]);
        r.push(&[]);
        r.push(&[7, 8, 9]);
        assert_eq!(r.len(), 3);
        assert_eq!(&r[0], &[3, 1]);
        assert!(r[1].is_empty());
        assert_eq!(r.to_vecs(), vec![vec![3, 1], vec![], vec![7, 8, 9]]);
        r.pop();
        assert_eq!(r.to_vecs(), vec![vec![3, 1], vec![]]);
        r.push(&[5]);
        assert_eq!(&r[2], &[5]);
        assert_eq!(r.iter().map(<[usize]>::len).sum::<usize>(), 3);
    }

    #[test]
    fn grouped_rows_keep_the_order_of_their_pairs() {
        let pairs = [(2, 7), (0, 1), (2, 3), (0, 5)];
        let r = Rows::grouped(4, || pairs.iter().copied());
        assert_eq!(r.to_vecs(), vec![vec![1, 5], vec![], vec![7, 3], vec![]]);
        assert!(Rows::grouped(0, std::iter::empty).is_empty());
    }
}
