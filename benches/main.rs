//! Criterion benches of jbearing, one binary: kernel, sweep and cycle groups.
use criterion::{criterion_group, criterion_main};

mod inverse;
mod kernel;
mod mobility;

criterion_group!(benches, kernel::bench, mobility::bench, inverse::bench);
criterion_main!(benches);
