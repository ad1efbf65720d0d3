//! Criterion benches of jbearing, one binary: kernel, sweep and cycle groups.
use criterion::{criterion_group, criterion_main};

mod mobility;
mod reynolds;

criterion_group!(benches, mobility::bench, reynolds::bench);
criterion_main!(benches);
