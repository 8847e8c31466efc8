//! [`Shard`]: one of `N` parts of a sweep, for running it across machines,
//! and [`interleave`], which puts the parts' results back in order.

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

use crate::LabError;

/// Part `index` of `count` (`index < count`): of a sweep's jobs, numbered
/// from 0 in report order, it runs those with `job % count == index`. The
/// dealing depends only on the job's number, so every machine agrees on it
/// and the parts' results interleave back into the unsharded order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Shard {
    /// Which part, from 0.
    pub index: usize,
    /// How many parts.
    pub count: usize,
}

impl Shard {
    /// Whether this part runs job number `job`.
    #[must_use]
    pub fn takes(self, job: usize) -> bool {
        job % self.count == self.index
    }

    /// The part's share of `jobs`, in order.
    #[must_use]
    pub fn deal<T: Clone>(self, jobs: &[T]) -> Vec<T> {
        jobs.iter()
            .enumerate()
            .filter(|&(k, _)| self.takes(k))
            .map(|(_, job)| job.clone())
            .collect()
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

impl FromStr for Shard {
    type Err = LabError;

    /// `I/N` with `0 ≤ I < N`.
    ///
    /// ```
    /// use hooke_lab::Shard;
    /// let shard: Shard = "2/3".parse()?;
    /// assert_eq!(shard, Shard { index: 2, count: 3 });
    /// assert!("3/3".parse::<Shard>().is_err());
    /// # Ok::<(), hooke_lab::LabError>(())
    /// ```
    fn from_str(text: &str) -> Result<Self, LabError> {
        let invalid = || LabError::Invalid {
            name: "shard",
            value: text.to_owned(),
            expected: "I/N with 0 ≤ I < N, e.g. 0/4",
        };
        let (index, count) = text.split_once('/').ok_or_else(invalid)?;
        let index: usize = index.trim().parse().map_err(|_| invalid())?;
        let count: usize = count.trim().parse().map_err(|_| invalid())?;
        if index < count {
            Ok(Self { index, count })
        } else {
            Err(invalid())
        }
    }
}

/// The results of parts `0..N` (`parts[i]` from part `i`, in its order)
/// put back into the order of the jobs they were dealt from; `None` if the
/// parts' sizes are not those of one dealing.
#[must_use]
pub fn interleave<T>(parts: Vec<Vec<T>>) -> Option<Vec<T>> {
    let count = parts.len();
    let total: usize = parts.iter().map(Vec::len).sum();
    let dealt = |i: usize| total / count + usize::from(i < total % count);
    if count == 0 || parts.iter().enumerate().any(|(i, p)| p.len() != dealt(i)) {
        return None;
    }
    let mut iters: Vec<_> = parts.into_iter().map(Vec::into_iter).collect();
    (0..total).map(|k| iters[k % count].next()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dealing_then_interleaving_gives_the_jobs_back() {
        let jobs: Vec<usize> = (0..11).collect();
        for count in 1..=12 {
            let parts: Vec<Vec<usize>> = (0..count)
                .map(|index| Shard { index, count }.deal(&jobs))
                .collect();
            assert_eq!(interleave(parts), Some(jobs.clone()), "{count} parts");
        }
        assert_eq!(interleave(vec![vec![0], vec![1, 3]]), None);
        assert_eq!(interleave::<usize>(Vec::new()), None);
    }

    #[test]
    fn a_malformed_shard_is_an_error_naming_it() {
        for text in ["", "1", "a/3", "1/0", "4/2", "-1/2"] {
            let error = text.parse::<Shard>().unwrap_err();
            assert!(error.to_string().contains("shard"), "{text}: {error}");
        }
    }
}
