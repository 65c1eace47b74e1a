use criterion::{criterion_group, criterion_main, Criterion};

fn bench_factor(_c: &mut Criterion) {
    // Placeholder: benchmarks will be added after factorization is implemented
}

criterion_group!(benches, bench_factor);
criterion_main!(benches);
