//! Criterion benches of jbearing, one binary: kernel, sweep and cycle groups.
use criterion::{Criterion, criterion_group, criterion_main};

mod inverse;
mod mobility;

fn placeholder(_c: &mut Criterion) {}

criterion_group!(benches, placeholder, mobility::bench, inverse::bench);
criterion_main!(benches);
