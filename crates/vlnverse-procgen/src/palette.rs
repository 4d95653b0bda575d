//! Colour and material finishes per class: the words instructions use ("the red mug") and the
//! linear RGB the renderer shows, kept in one table so they always agree.

use rand::seq::IndexedRandom;
use rand_chacha::ChaCha8Rng;
use vlnverse_env::SemanticClass as C;

/// A colour word, a material word and the base colour of an object's main parts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Finish {
    pub color: &'static str,
    pub material: &'static str,
    pub rgb: [f32; 3],
    /// The tone of the colour word, if one was taken (`crate::tones`).
    pub shade: Option<&'static str>,
}

/// A finish from its colour word, material word and linear RGB.
pub(crate) const fn f(color: &'static str, material: &'static str, rgb: [f32; 3]) -> Finish {
    Finish {
        color,
        material,
        rgb,
        shade: None,
    }
}

/// Wood finishes, the plain ones first (`pieces.rs` takes the first four).
pub(crate) const WOOD: &[Finish] = &[
    f("wooden", "wood", [0.45, 0.27, 0.13]),
    f("brown", "wood", [0.26, 0.15, 0.07]),
    f("white", "wood", [0.85, 0.85, 0.82]),
    f("black", "wood", [0.05, 0.05, 0.05]),
    f("grey", "wood", [0.35, 0.35, 0.36]),
    f("blue", "wood", [0.12, 0.22, 0.45]),
    f("green", "wood", [0.16, 0.32, 0.2]),
];
const FABRIC: &[Finish] = &[
    f("red", "fabric", [0.55, 0.06, 0.06]),
    f("blue", "fabric", [0.08, 0.16, 0.5]),
    f("grey", "fabric", [0.3, 0.3, 0.32]),
    f("green", "fabric", [0.12, 0.38, 0.14]),
    f("beige", "fabric", [0.7, 0.6, 0.45]),
    f("yellow", "fabric", [0.8, 0.62, 0.08]),
    f("brown", "leather", [0.28, 0.14, 0.06]),
    f("black", "leather", [0.04, 0.04, 0.04]),
    f("white", "fabric", [0.85, 0.85, 0.85]),
    f("purple", "fabric", [0.2, 0.06, 0.28]),
];
const CHAIR: &[Finish] = &[
    f("wooden", "wood", [0.45, 0.27, 0.13]),
    f("brown", "wood", [0.26, 0.15, 0.07]),
    f("black", "metal", [0.05, 0.05, 0.05]),
    f("white", "plastic", [0.88, 0.88, 0.88]),
    f("red", "plastic", [0.6, 0.05, 0.05]),
    f("blue", "fabric", [0.08, 0.16, 0.5]),
    f("green", "fabric", [0.12, 0.38, 0.14]),
    f("grey", "fabric", [0.3, 0.3, 0.32]),
    f("yellow", "plastic", [0.85, 0.68, 0.08]),
];
const CERAMIC: &[Finish] = &[
    f("white", "ceramic", [0.9, 0.9, 0.9]),
    f("blue", "ceramic", [0.1, 0.25, 0.6]),
    f("red", "ceramic", [0.6, 0.08, 0.06]),
    f("yellow", "ceramic", [0.85, 0.7, 0.1]),
    f("green", "ceramic", [0.15, 0.45, 0.2]),
    f("black", "ceramic", [0.05, 0.05, 0.05]),
    f("orange", "ceramic", [0.75, 0.32, 0.08]),
    f("grey", "ceramic", [0.4, 0.4, 0.42]),
];
const SANITARY: &[Finish] = &[
    f("white", "ceramic", [0.92, 0.92, 0.92]),
    f("grey", "ceramic", [0.55, 0.55, 0.57]),
    f("beige", "ceramic", [0.78, 0.72, 0.6]),
];
const APPLIANCE: &[Finish] = &[
    f("white", "metal", [0.88, 0.88, 0.88]),
    f("silver", "metal", [0.6, 0.6, 0.62]),
    f("black", "metal", [0.06, 0.06, 0.06]),
    f("red", "metal", [0.6, 0.06, 0.05]),
];
const SCREEN: &[Finish] = &[
    f("black", "plastic", [0.03, 0.03, 0.03]),
    f("silver", "metal", [0.6, 0.6, 0.62]),
    f("white", "plastic", [0.88, 0.88, 0.88]),
];
const PLASTIC: &[Finish] = &[
    f("red", "plastic", [0.6, 0.05, 0.05]),
    f("blue", "plastic", [0.08, 0.2, 0.6]),
    f("green", "plastic", [0.1, 0.45, 0.15]),
    f("yellow", "plastic", [0.85, 0.7, 0.08]),
    f("white", "plastic", [0.88, 0.88, 0.88]),
    f("black", "plastic", [0.04, 0.04, 0.04]),
    f("grey", "plastic", [0.4, 0.4, 0.42]),
];
const PAPER: &[Finish] = &[
    f("red", "paper", [0.55, 0.07, 0.07]),
    f("blue", "paper", [0.08, 0.18, 0.5]),
    f("green", "paper", [0.12, 0.4, 0.16]),
    f("yellow", "paper", [0.85, 0.7, 0.12]),
    f("black", "paper", [0.05, 0.05, 0.05]),
    f("white", "paper", [0.88, 0.88, 0.85]),
    f("orange", "paper", [0.8, 0.35, 0.08]),
];
const GLASS: &[Finish] = &[
    f("green", "glass", [0.1, 0.4, 0.15]),
    f("brown", "glass", [0.3, 0.15, 0.05]),
    f("blue", "glass", [0.1, 0.25, 0.6]),
    f("white", "glass", [0.8, 0.85, 0.85]),
];
const METAL: &[Finish] = &[
    f("silver", "metal", [0.6, 0.6, 0.62]),
    f("black", "metal", [0.05, 0.05, 0.05]),
    f("white", "metal", [0.88, 0.88, 0.88]),
    f("gold", "metal", [0.75, 0.55, 0.15]),
];
const LAMP: &[Finish] = &[
    f("white", "fabric", [0.9, 0.88, 0.82]),
    f("yellow", "fabric", [0.85, 0.7, 0.2]),
    f("black", "metal", [0.05, 0.05, 0.05]),
    f("red", "fabric", [0.6, 0.08, 0.06]),
    f("blue", "fabric", [0.1, 0.2, 0.55]),
    f("grey", "fabric", [0.45, 0.45, 0.47]),
];
const POT: &[Finish] = &[
    f("orange", "ceramic", [0.65, 0.3, 0.12]),
    f("white", "ceramic", [0.9, 0.9, 0.9]),
    f("grey", "ceramic", [0.4, 0.4, 0.42]),
    f("blue", "ceramic", [0.1, 0.25, 0.6]),
    f("black", "ceramic", [0.05, 0.05, 0.05]),
];
const WAX: &[Finish] = &[
    f("white", "wax", [0.92, 0.9, 0.85]),
    f("red", "wax", [0.6, 0.06, 0.06]),
    f("yellow", "wax", [0.85, 0.72, 0.2]),
];
const RUG: &[Finish] = &[
    f("red", "fabric", [0.5, 0.07, 0.07]),
    f("blue", "fabric", [0.1, 0.18, 0.45]),
    f("grey", "fabric", [0.35, 0.35, 0.37]),
    f("beige", "fabric", [0.7, 0.62, 0.48]),
    f("green", "fabric", [0.14, 0.34, 0.16]),
    f("yellow", "fabric", [0.75, 0.6, 0.15]),
    f("brown", "fabric", [0.3, 0.17, 0.08]),
    f("purple", "fabric", [0.24, 0.08, 0.3]),
];
const WICKER: &[Finish] = &[
    f("brown", "wicker", [0.4, 0.25, 0.12]),
    f("beige", "wicker", [0.7, 0.58, 0.38]),
    f("white", "plastic", [0.88, 0.88, 0.88]),
    f("grey", "plastic", [0.4, 0.4, 0.42]),
];
const CARDBOARD: &[Finish] = &[
    f("brown", "cardboard", [0.45, 0.3, 0.15]),
    f("beige", "cardboard", [0.62, 0.5, 0.32]),
];
const STONE: &[Finish] = &[
    f("white", "stone", [0.82, 0.8, 0.76]),
    f("grey", "stone", [0.42, 0.42, 0.43]),
    f("red", "brick", [0.45, 0.15, 0.08]),
];
const TISSUE: &[Finish] = &[f("white", "paper", [0.9, 0.9, 0.88])];
const TOWEL: &[Finish] = &[
    f("white", "fabric", [0.9, 0.9, 0.9]),
    f("blue", "fabric", [0.1, 0.25, 0.6]),
    f("pink", "fabric", [0.85, 0.45, 0.55]),
    f("yellow", "fabric", [0.85, 0.72, 0.2]),
    f("green", "fabric", [0.15, 0.45, 0.2]),
    f("purple", "fabric", [0.3, 0.12, 0.4]),
];

/// Candidate finishes of a class.
fn choices(class: C) -> &'static [Finish] {
    match class {
        C::Sofa | C::Armchair | C::OfficeChair | C::Bench => FABRIC,
        C::Chair | C::Stool => CHAIR,
        C::Toilet | C::Sink | C::Bathtub | C::Shower => SANITARY,
        C::Fridge
        | C::Stove
        | C::Dishwasher
        | C::WashingMachine
        | C::Toaster
        | C::Kettle
        | C::Microwave => APPLIANCE,
        C::Tv | C::Monitor | C::Laptop | C::Keyboard | C::Remote => SCREEN,
        C::Cup | C::Mug | C::Bowl | C::Plate | C::Vase | C::SoapDispenser => CERAMIC,
        C::PottedPlant | C::SmallPlant => POT,
        C::FloorLamp | C::TableLamp => LAMP,
        C::Book => PAPER,
        C::Bottle => GLASS,
        C::Clock | C::TrashCan => PLASTIC,
        C::CoatRack | C::Mirror | C::PictureFrame => METAL,
        C::Candle => WAX,
        C::Rug => RUG,
        C::Towel | C::Pillow => TOWEL,
        C::Ottoman
        | C::BeanBag
        | C::DogBed
        | C::Backpack
        | C::Shoes
        | C::Slippers
        | C::YogaMat
        | C::Curtain => FABRIC,
        C::Basket | C::LaundryBasket => WICKER,
        C::Box => CARDBOARD,
        C::Fireplace => STONE,
        C::Pot | C::Pan => APPLIANCE,
        C::FruitBowl | C::Teapot => CERAMIC,
        C::CoffeeMachine | C::Blender | C::Printer | C::Heater | C::Radiator => APPLIANCE,
        C::Speaker | C::Phone | C::Tablet | C::Headphones | C::Treadmill => SCREEN,
        C::Hairdryer
        | C::Shampoo
        | C::ToothbrushHolder
        | C::TissueBox
        | C::PenHolder
        | C::Toy
        | C::Globe
        | C::DishRack
        | C::Fan
        | C::PatioChair
        | C::PatioTable
        | C::HighChair
        | C::UmbrellaStand => PLASTIC,
        C::BoardGame | C::Magazine => PAPER,
        C::ToiletPaper => TISSUE,
        C::Planter => POT,
        C::FilingCabinet
        | C::ShelvingUnit
        | C::Bicycle
        | C::ExerciseBike
        | C::IroningBoard
        | C::DryingRack
        | C::ClothesRail
        | C::Dumbbells => METAL,
        _ => WOOD,
    }
}

/// Draw a finish for an object of `class`, in one of its colour word's tones or its own.
pub(crate) fn pick(class: C, rng: &mut ChaCha8Rng) -> Finish {
    let list = choices(class);
    let fin = *list.choose(rng).unwrap_or(&list[0]);
    crate::tones::toned(fin, rng)
}

/// Draw a fabric colour (bedding, cushions).
pub(crate) fn fabric(rng: &mut ChaCha8Rng) -> [f32; 3] {
    FABRIC.choose(rng).map_or([0.5; 3], |f| f.rgb)
}

/// Coulomb friction of a material word.
pub(crate) fn friction(material: &str) -> f32 {
    match material {
        "fabric" | "leather" | "carpet" => 0.7,
        "metal" | "glass" => 0.35,
        "plastic" => 0.45,
        "paper" => 0.55,
        _ => 0.5,
    }
}

/// Darker (f < 1) or lighter (f > 1) version of a colour.
pub(crate) fn shade(rgb: [f32; 3], f: f32) -> [f32; 3] {
    rgb.map(|c| (c * f).clamp(0.0, 1.0))
}

/// A few fixed colours for details.
pub(crate) mod tone {
    /// Dark metal (legs, handles).
    pub const METAL: [f32; 3] = [0.12, 0.12, 0.13];
    /// Bright steel.
    pub const STEEL: [f32; 3] = [0.65, 0.65, 0.68];
    /// Screen glass.
    pub const SCREEN: [f32; 3] = [0.02, 0.02, 0.03];
    /// White ceramic / porcelain.
    pub const WHITE: [f32; 3] = [0.92, 0.92, 0.92];
    /// Foliage.
    pub const LEAF: [f32; 3] = [0.1, 0.38, 0.1];
    /// Soil.
    pub const SOIL: [f32; 3] = [0.18, 0.11, 0.06];
    /// Mattress / linen.
    pub const LINEN: [f32; 3] = [0.9, 0.9, 0.86];
    /// Light wood.
    pub const WOOD: [f32; 3] = [0.5, 0.32, 0.16];
    /// Glass panels.
    pub const GLASS: [f32; 3] = [0.7, 0.8, 0.85];
    /// Fruit.
    pub const FRUIT_RED: [f32; 3] = [0.62, 0.06, 0.04];
    /// Fruit, a toy's cab.
    pub const FRUIT_YELLOW: [f32; 3] = [0.85, 0.7, 0.1];
    /// Fruit, embers.
    pub const FRUIT_ORANGE: [f32; 3] = [0.85, 0.35, 0.05];
    /// Soot, tyres.
    pub const SOOT: [f32; 3] = [0.03, 0.03, 0.03];
    /// Aquarium water.
    pub const WATER: [f32; 3] = [0.2, 0.45, 0.55];
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    /// Hue in degrees of a linear RGB (0 for greys).
    fn hue(rgb: [f32; 3]) -> f32 {
        let [r, g, b] = rgb;
        let (hi, lo) = (r.max(g).max(b), r.min(g).min(b));
        if hi - lo < 1e-6 {
            return 0.0;
        }
        let d = hi - lo;
        let h = if hi == r {
            ((g - b) / d).rem_euclid(6.0)
        } else if hi == g {
            (b - r) / d + 2.0
        } else {
            (r - g) / d + 4.0
        };
        h * 60.0
    }

    #[test]
    fn purple_finishes_and_their_tones_read_as_purple() {
        let purples: Vec<Finish> = [FABRIC, RUG, TOWEL]
            .iter()
            .flat_map(|l| l.iter())
            .filter(|f| f.color == "purple")
            .copied()
            .collect();
        assert_eq!(purples.len(), 3);
        let mut shades = std::collections::BTreeSet::new();
        for fin in purples {
            for seed in 0..200 {
                let t = crate::tones::toned(fin, &ChaCha8Rng::seed_from_u64(seed));
                assert_eq!(t.color, "purple");
                let h = hue(t.rgb);
                // Between blue (240) and magenta-red (345), with some saturation.
                let sat = 1.0
                    - t.rgb.iter().copied().fold(1.0, f32::min)
                        / t.rgb.iter().copied().fold(0.0, f32::max);
                assert!((255.0..345.0).contains(&h) && sat > 0.25, "{t:?}: hue {h}");
                shades.insert(t.shade);
            }
        }
        for s in ["lavender", "plum", "violet"] {
            assert!(shades.contains(&Some(s)), "{shades:?}");
        }
    }
}
