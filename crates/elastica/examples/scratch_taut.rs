//! scratch
use elastica::stability::follow::{DiscreteBlade, HeldEnds};
use elastica::{ElasticaParams, Family, Segment};
fn main() {
    for (omk, s0, l, scale) in [(
        1.0 - 0.9999978750330576,
        -9.653054687935901,
        4.265833181384783,
        187.53663492774052,
    )] {
        let s = Segment::Elastica(ElasticaParams {
            family: Family::Inflectional,
            k: 1.0 - omk,
            s0,
            l,
            scale,
            phi: 3.132523465917769,
            x0: 0.0,
            y0: 0.0,
            one_minus_k: None,
        });
        let st = elastica::stability(&s, &Default::default()).unwrap();
        let e = s.evaluator().unwrap();
        let (a, b) = (e.eval(0.0), e.eval(1.0));
        let ca = (b.p[1] - a.p[1]).atan2(b.p[0] - a.p[0]);
        let ends = HeldEnds {
            chord: (b.p[0] - a.p[0]).hypot(b.p[1] - a.p[1]),
            angles: [a.angle - ca, b.angle - ca],
        };
        print!(
            "omk {omk:e} L {:.1} chord {:.4} angles {:?} closed {:.4} infl {} load {:?} |",
            s.length(),
            ends.chord,
            ends.angles,
            st.margin,
            st.inflections,
            st.loads.multipliers
        );
        for n in [128, 256, 512] {
            match DiscreteBlade::settle_like(s.length(), ends, |u| e.eval(u).angle - ca, n, None) {
                Ok(d) => print!(" n{n} {:.4}", d.margin().unwrap()),
                Err(_) => print!(" n{n} fail"),
            }
        }
        for cells in [64, 256, 1024] {
            let m = elastica::stability::margin_of(
                s.length(),
                |x| e.eval(x / s.length()).angle,
                elastica::stability::multipliers(&s),
                cells,
            )
            .unwrap();
            print!(" c{cells} {m:.4}");
        }
        println!();
    }
}
