//! Criterion benches of jbearing, one binary: kernel, sweep and cycle groups.
use criterion::{criterion_group, criterion_main};

mod kernel;
mod mobility;

criterion_group!(benches, kernel::bench, mobility::bench);
criterion_main!(benches);
