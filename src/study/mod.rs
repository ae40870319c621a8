//! Studies over many plans: layouts compared ([`compare`]), populations swept ([`sweep`]), both
//! split into deterministic shards ([`shard`]) that merge into the result of one run.

pub mod compare;
pub mod shard;
pub mod sweep;
pub mod what_if;
