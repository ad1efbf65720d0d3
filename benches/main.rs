//! Criterion benches of jbearing, one binary: kernel, sweep and cycle groups.
use criterion::{criterion_group, criterion_main};

mod kernel;
mod mobility;
mod reynolds;

criterion_group!(benches, kernel::bench, mobility::bench, reynolds::bench);
criterion_main!(benches);
