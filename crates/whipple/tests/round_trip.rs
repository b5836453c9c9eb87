//! Every writer reads back to the identical bicycle, every field: TOML and JSON bit for bit
//! (names and sources included), JBike6's `.m` listing to the 8 decimals of its layout (exactly
//! for the presets, whose digits fit). For every preset and, as property tests, for random
//! bicycles in both forms.

use proptest::prelude::*;
use whipple::advanced::io::{Format, parse, write};
use whipple::advanced::parameters::{Description, Jbike6Parameters};
use whipple::presets::PRESETS;
use whipple::{BenchmarkParameters, Bicycle};

fn round_trip(bike: &Bicycle, format: Format) -> Bicycle {
    let text = write(bike, format).expect("every bicycle can be written");
    parse(&text, format).unwrap_or_else(|e| panic!("{format:?} does not read back: {e}\n{text}"))
}

#[test]
fn every_preset_reads_back_identically_in_every_format() {
    for preset in PRESETS {
        let bike = preset.bicycle();
        for format in [Format::Toml, Format::Json] {
            assert_eq!(
                round_trip(&bike, format),
                bike,
                "{} in {format:?}",
                preset.name
            );
        }
        if let Description::Jbike6(p) = &bike.description {
            let back = round_trip(&bike, Format::Jbike6M);
            assert_eq!(back.jbike6(), Some(p), "{} in .m", preset.name);
        } else {
            // A benchmark bicycle goes to .m as JBike6's bodies; read back and combined, it is
            // the same 25 numbers and g (see `benchmark_presets_through_jbike6_bodies`).
            let back = round_trip(&bike, Format::Jbike6M);
            assert!(back.jbike6().is_some(), "{} in .m", preset.name);
        }
    }
}

/// Benchmark → JBike6's bodies in a `.m` file → read → combined into the benchmark form: every
/// preset's 25 numbers and g back to 1e-12 (relative to the number; for a tensor entry, to the
/// body's largest moment; for a position, to the wheelbase).
#[test]
fn benchmark_presets_through_jbike6_bodies() {
    for preset in PRESETS {
        let Description::Benchmark(b) = preset.bicycle().description else {
            continue;
        };
        let text = write(&preset.bicycle(), Format::Jbike6M).expect("written");
        let back = parse(&text, Format::Jbike6M)
            .expect("read back")
            .benchmark()
            .unwrap_or_else(|e| panic!("{}: {e}\n{text}", preset.name));
        let scale_b = b.i_bxx.abs().max(b.i_bzz.abs());
        let scale_h = b.i_hxx.abs().max(b.i_hzz.abs());
        for ((key, x), (_, y)) in b.fields().into_iter().zip(back.fields()) {
            let scale = match key {
                "IBxx" | "IBzz" | "IBxz" => scale_b,
                "IHxx" | "IHzz" | "IHxz" => scale_h,
                "xB" | "zB" | "xH" | "zH" | "c" => b.w,
                _ => x.abs(),
            };
            assert!(
                (x - y).abs() <= 1e-12 * scale,
                "{} {key}: {x} vs {y}",
                preset.name
            );
        }
        // Written again, the file is the same bicycle's JBike6 form: equal bodies.
        let jbike6 = Jbike6Parameters::from_benchmark(&b);
        assert_eq!(
            parse(&text, Format::Jbike6M).unwrap().jbike6(),
            Some(&jbike6)
        );
    }
}

/// Any finite number: ordinary sizes, tiny and huge magnitudes, both signs, zero and
/// subnormals (a writer must not care whether the bicycle is valid).
fn number() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => -10.0..10.0f64,
        1 => prop::num::f64::NORMAL,
        1 => prop::num::f64::SUBNORMAL | prop::num::f64::ZERO,
    ]
}

/// A name or source: any characters, quotes, backslashes, newlines and non-ASCII included.
fn text() -> impl Strategy<Value = Option<String>> {
    prop::option::of(
        prop::collection::vec(
            prop_oneof![any::<char>(), Just('"'), Just('\\'), Just('\n'), Just('#')],
            0..24,
        )
        .prop_map(|chars| chars.into_iter().collect::<String>()),
    )
}

fn benchmark(v: &[f64]) -> BenchmarkParameters {
    BenchmarkParameters {
        w: v[0],
        c: v[1],
        lambda: v[2],
        g: v[3],
        r_r: v[4],
        m_r: v[5],
        i_rxx: v[6],
        i_ryy: v[7],
        x_b: v[8],
        z_b: v[9],
        m_b: v[10],
        i_bxx: v[11],
        i_byy: v[12],
        i_bzz: v[13],
        i_bxz: v[14],
        x_h: v[15],
        z_h: v[16],
        m_h: v[17],
        i_hxx: v[18],
        i_hyy: v[19],
        i_hzz: v[20],
        i_hxz: v[21],
        r_f: v[22],
        m_f: v[23],
        i_fxx: v[24],
        i_fyy: v[25],
    }
}

/// A JBike6 bicycle with every one of its 51 numbers replaced.
fn jbike6(v: &[f64]) -> Jbike6Parameters {
    let mut p = whipple::presets::schwinn_crown_jbike6();
    let mut next = v.iter().copied();
    let mut n = || next.next().unwrap_or(0.0);
    p.wheelbase = n();
    p.head_angle = n();
    p.trail = n();
    p.gravity = n();
    for w in [&mut p.rear_wheel, &mut p.front_wheel] {
        w.diameter = n();
        w.m = n();
        w.inertia = [n(), n(), n()];
        w.alpha = n();
    }
    for b in [&mut p.rider, &mut p.frame, &mut p.rack] {
        b.m = n();
        b.xcm = n();
        b.ycm = n();
        b.inertia = [n(), n(), n()];
        b.alpha = n();
    }
    for b in [&mut p.fork, &mut p.basket] {
        b.m = n();
        b.ucm = n();
        b.vcm = n();
        b.inertia = [n(), n(), n()];
        b.alpha = n();
    }
    p
}

fn jbike6_numbers(p: &Jbike6Parameters) -> Vec<f64> {
    let mut out = vec![p.wheelbase, p.head_angle, p.trail, p.gravity];
    for w in [&p.rear_wheel, &p.front_wheel] {
        out.extend([w.diameter, w.m]);
        out.extend(w.inertia);
        out.push(w.alpha);
    }
    for b in [&p.rider, &p.frame, &p.rack] {
        out.extend([b.m, b.xcm, b.ycm]);
        out.extend(b.inertia);
        out.push(b.alpha);
    }
    for b in [&p.fork, &p.basket] {
        out.extend([b.m, b.ucm, b.vcm]);
        out.extend(b.inertia);
        out.push(b.alpha);
    }
    out
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 256,
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn random_benchmark_bicycles_read_back_identically(
        v in prop::collection::vec(number(), 26),
        name in text(),
        source in text(),
    ) {
        let bike = Bicycle { name, source, ..Bicycle::new(Description::Benchmark(benchmark(&v))) };
        for format in [Format::Toml, Format::Json] {
            prop_assert_eq!(&round_trip(&bike, format), &bike, "{:?}", format);
        }
    }

    #[test]
    fn random_jbike6_bicycles_read_back_identically(
        v in prop::collection::vec(number(), 51),
        name in text(),
        source in text(),
    ) {
        let p = jbike6(&v);
        prop_assert_eq!(jbike6_numbers(&p), v.clone());
        let bike = Bicycle { name, source, ..Bicycle::new(Description::Jbike6(p)) };
        for format in [Format::Toml, Format::Json] {
            prop_assert_eq!(&round_trip(&bike, format), &bike, "{:?}", format);
        }
        // The .m layout prints 8 decimals, as JBike6 does (and keeps no source).
        let back = round_trip(&bike, Format::Jbike6M);
        let back = jbike6_numbers(back.jbike6().expect("a JBike6 bicycle"));
        for (x, y) in back.iter().zip(&v) {
            prop_assert!((x - y).abs() <= 5e-9 + 4.0 * f64::EPSILON * y.abs(), "{} vs {}", x, y);
        }
    }
}
