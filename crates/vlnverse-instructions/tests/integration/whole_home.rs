//! A fine instruction described on one floor of a home (`PathContext::whole_home`) says "the
//! only one in the house" only of what the whole home holds once.

use crate::instructions_fixture::{paths, worlds, Ctx};
use vlnverse_instructions::{InstructionGenerator, TemplateGenerator};

/// Whether a text says its end object is the only one of its class in the home.
fn says_only_one(text: &str) -> bool {
    let t = text.to_lowercase();
    ["only one", "the only", "just one"]
        .iter()
        .any(|p| t.contains(p) && (t.contains("in the house") || t.contains("in the home")))
}

#[test]
fn the_only_one_in_the_house_is_counted_in_the_whole_home() {
    let g = TemplateGenerator::default();
    let (mut alone, mut with_home) = (0, 0);
    for w in worlds(3) {
        // The same home with a second copy of every object: nothing in it is the only one.
        let mut home = w.scene.clone();
        let n = home.objects.len() as u32;
        let copies: Vec<_> = home
            .objects
            .iter()
            .map(|o| {
                let mut c = o.clone();
                c.id += n;
                c
            })
            .collect();
        home.objects.extend(copies);
        for s in paths(&w, 40, 5) {
            let mut ctx = w.ctx(&s);
            for seed in 0..25 {
                if says_only_one(&g.fine(&ctx, seed).unwrap().instruction_text) {
                    alone += 1;
                }
            }
            ctx.whole_home = Some(&home);
            for seed in 0..25 {
                let text = g.fine(&ctx, seed).unwrap().instruction_text;
                if says_only_one(&text) {
                    with_home += 1;
                    eprintln!("{text}");
                }
            }
        }
    }
    // Said of a floor's only object when the floor is the home; never when the home has two.
    assert!(alone > 0, "the remark never came up");
    assert_eq!(with_home, 0);
}
