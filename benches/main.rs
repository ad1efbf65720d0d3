//! Criterion benches of jbearing, one binary: kernel, sweep and cycle groups.
use criterion::{Criterion, criterion_group, criterion_main};

mod mobility;

fn placeholder(_c: &mut Criterion) {}

criterion_group!(benches, placeholder, mobility::bench);
criterion_main!(benches);
