//! Deterministic shards of a study: item `j` of `total` belongs to shard `j mod n`.

use serde::{Deserialize, Serialize};

/// Shard `index` (0-based) of `count`, written `i/n` with `i` 1-based on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Shard {
    pub index: usize,
    pub count: usize,
}

impl Shard {
    /// The whole study as one shard.
    pub const ALL: Shard = Shard { index: 0, count: 1 };

    /// The items of `total` this shard runs, in order.
    pub fn indices(&self, total: usize) -> Vec<usize> {
        (self.index..total).step_by(self.count).collect()
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index + 1, self.count)
    }
}

impl std::str::FromStr for Shard {
    type Err = String;
    /// Parses `i/n` with 1 ≤ i ≤ n ≤ 10000.
    fn from_str(s: &str) -> Result<Self, String> {
        let bad =
            || format!("a shard is written i/n with 1 <= i <= n <= 10000 (e.g. 2/4), got '{s}'");
        let (i, n) = s.split_once('/').ok_or_else(bad)?;
        let i: usize = i.trim().parse().map_err(|_| bad())?;
        let n: usize = n.trim().parse().map_err(|_| bad())?;
        if i == 0 || i > n || n > 10_000 {
            return Err(bad());
        }
        Ok(Shard {
            index: i - 1,
            count: n,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_partition_the_items() {
        for total in [0usize, 1, 5, 17] {
            for n in 1..6 {
                let mut all: Vec<usize> = (1..=n)
                    .flat_map(|i| format!("{i}/{n}").parse::<Shard>().unwrap().indices(total))
                    .collect();
                all.sort();
                assert_eq!(all, (0..total).collect::<Vec<_>>());
            }
        }
        for bad in ["0/3", "4/3", "1", "a/b", "1/0", "1/20000"] {
            assert!(bad.parse::<Shard>().is_err(), "{bad}");
        }
    }
}
