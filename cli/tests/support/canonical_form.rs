//! The canonical form `chaplygin linearize --canonical` prints, read back
//! and compared entry by entry.

/// The matrix printed under `name:`: a header row naming the columns `q`,
/// then one row per coordinate, its name first.
pub fn printed_matrix(text: &str, name: &str, q: [&str; 2]) -> [[f64; 2]; 2] {
    let mut lines = text
        .lines()
        .skip_while(|line| *line != format!("{name}:"))
        .skip(1);
    let header: Vec<&str> = lines.next().expect("a header").split_whitespace().collect();
    assert_eq!(header, q, "{text}");
    let row = |coordinate: &str| -> [f64; 2] {
        let fields: Vec<&str> = lines.next().expect("a row").split_whitespace().collect();
        assert_eq!(fields[0], coordinate, "{text}");
        [fields[1], fields[2]].map(|field| field.parse().expect("a number"))
    };
    q.map(row)
}

/// Every entry of `found` within 1e-12 of `expected`'s, relative (absolute
/// where it is 0).
pub fn assert_entries(found: &[[f64; 2]; 2], expected: &[[f64; 2]; 2], what: &str) {
    for i in 0..2 {
        for j in 0..2 {
            let (f, e) = (found[i][j], expected[i][j]);
            let scale = if e == 0.0 { 1.0 } else { e.abs() };
            assert!(
                (f - e).abs() <= 1e-12 * scale,
                "{what}[{i}][{j}]: {f:.16e} vs {e:.16e}, {:e} relative",
                (f - e).abs() / scale
            );
        }
    }
}
