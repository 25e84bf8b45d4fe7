pub fn check_outputs(plan: &Plan, before: &[u8], after: &[u8], triangles: &[[usize; 3]]) {
    let b = &plan.bufs;
    let vc = plan.vertex_count;
    let tangent = |i: usize| -> [f32; 4] { vec_at(after, b[TAN].element(i)) };
    let bitangent = |i: usize| -> Option<[f32; 3]> { (!b[BIT].null).then(|| vec_at(after, b[BIT].element(i))) };
    let normal = |i: usize| -> [f32; 3] { vec_at(before, b[NRM].element(i)) };

    if plan.effective_policy() == TBASIS_DEGENERATE_LEGACY {
        // The header promises the listing's bits for method LENGYEL; FLIP_V is not the listing.
        let listing_exact = plan.method == TBASIS_METHOD_LENGYEL && plan.flags & TBASIS_FLAG_FLIP_V == 0;
        if listing_exact {
            let expected = listing(
                vc,
                triangles,
                |i| vec_at(before, b[POS].element(i)),
                normal,
                |i| vec_at(before, b[UV].element(i)),
            );
            for (i, want) in expected.iter().enumerate() {
                let got = tangent(i);
                assert!(
                    (0..4).all(|k| same(got[k], want[k])),
                    "LEGACY tangent {i} is {got:?}, the listing gives {want:?}"
                );
            }
        }
        for i in 0..vc {
            let [x, y, z, w] = tangent(i);
            assert!(w == 1.0 || w == -1.0, "LEGACY w of vertex {i} is {w}");
            if let Some(got) = bitangent(i) {
                let n = normal(i);
                let c = [n[1] * z - n[2] * y, n[2] * x - n[0] * z, n[0] * y - n[1] * x];
                let want = c.map(|c| c * w);
                assert!(
                    (0..3).all(|k| same(got[k], want[k])),
                    "LEGACY bitangent {i} is {got:?}, w * cross(n, t) is {want:?}"
                );
            }
        }
        return;
    }

    for i in 0..vc {
        let t4 = tangent(i);
        let [x, y, z, w] = t4.map(f64::from);
        let t = [x, y, z];
        let context = || {
            format!(
                "vertex {i}: tangent {t4:?}, normal {:?}, bitangent {:?}",
                normal(i),
                bitangent(i)
            )
        };
        assert!(t4.iter().all(|v| v.is_finite()), "{}: not finite", context());
        assert!((length(t) - 1.0).abs() <= TOLERANCE, "{}: not unit length", context());
        assert!(w == 1.0 || w == -1.0, "{}: w is not +1 or -1", context());
        let n_hat = unit(normal(i));
        if let Some(n) = n_hat {
            assert!(
                dot(t, n).abs() <= TOLERANCE,
                "{}: not orthogonal to the normal",
                context()
            );
        }
        if let Some(b3) = bitangent(i) {
            let bv = b3.map(f64::from);
            assert!(b3.iter().all(|v| v.is_finite()), "{}: bitangent not finite", context());
            match n_hat {
                Some(n) => {
                    let want = cross(n, t).map(|c| c * w);
                    assert!(
                        (0..3).all(|k| (bv[k] - want[k]).abs() <= TOLERANCE),
                        "{}: bitangent is not w * cross(n, t)",
                        context()
                    );
                }
                None => {
                    assert!(
                        (length(bv) - 1.0).abs() <= TOLERANCE,
                        "{}: bitangent not unit",
                        context()
                    );
                    assert!(dot(bv, t).abs() <= TOLERANCE, "{}: bitangent not orthogonal", context());
                }
            }
        }
    }
}
