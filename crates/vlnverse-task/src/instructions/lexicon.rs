//! Words for the things a scene holds: class and room names with their everyday synonyms,
//! colour shades read from an object's rendered colour, material, size and shape words, and
//! numbers. Written for this project. Every word here is derived from data the scene model has
//! (class, room type, colour word, part colours, material word, bounding box, part shapes).

use vlnverse_env::{RoomType, SceneObject, SemanticClass as C, Shape};

/// Names of a class, the vocabulary name first. Every name maps back to one class only
/// ([`class_of_name`]), so a grounded object can be found in the text by any of them.
pub fn class_names(class: C) -> &'static [&'static str] {
    match class {
        C::Bed => &["bed"],
        C::Nightstand => &[
            "nightstand",
            "bedside table",
            "night table",
            "bedside cabinet",
        ],
        C::Wardrobe => &["wardrobe", "armoire", "clothes cupboard"],
        C::Dresser => &["dresser", "chest of drawers"],
        C::Toilet => &["toilet", "loo", "water closet"],
        C::Sink => &["sink", "basin", "washbasin"],
        C::Bathtub => &["bathtub", "bath", "tub"],
        C::Shower => &["shower", "shower stall", "shower cubicle"],
        C::Mirror => &["mirror", "looking glass"],
        C::Fridge => &["fridge", "refrigerator", "fridge freezer"],
        C::Counter => &["counter", "worktop", "countertop"],
        C::Stove => &["stove", "cooker", "oven", "range cooker"],
        C::Dishwasher => &["dishwasher", "dish washer"],
        C::KitchenCabinet => &["kitchen cabinet", "kitchen cupboard", "kitchen unit"],
        C::Sofa => &["sofa", "couch", "settee"],
        C::Armchair => &["armchair", "easy chair", "lounge chair"],
        C::Tv => &["tv", "television", "telly", "tv set"],
        C::TvStand => &["tv stand", "tv unit", "media console", "television stand"],
        C::CoffeeTable => &["coffee table", "low table", "cocktail table"],
        C::DiningTable => &["dining table", "dinner table", "kitchen table"],
        C::Chair => &["chair", "seat"],
        C::Desk => &["desk", "writing desk", "work desk"],
        C::OfficeChair => &["office chair", "desk chair", "swivel chair"],
        C::Bookshelf => &["bookshelf", "bookcase", "book shelf", "shelving unit"],
        C::PottedPlant => &["potted plant", "plant", "houseplant", "pot plant"],
        C::FloorLamp => &["floor lamp", "standing lamp", "lamp", "standard lamp"],
        C::Rug => &["rug", "carpet", "mat"],
        C::Cabinet => &["cabinet", "cupboard", "sideboard"],
        C::SideTable => &["side table", "end table", "small table"],
        C::ShoeRack => &["shoe rack", "shoe stand", "shoe shelf"],
        C::CoatRack => &["coat rack", "coat stand", "hat stand"],
        C::WashingMachine => &["washing machine", "washer", "laundry machine"],
        C::Piano => &["piano", "upright piano"],
        C::Bench => &["bench"],
        C::Stool => &["stool", "footstool"],
        C::TrashCan => &[
            "trash can",
            "bin",
            "rubbish bin",
            "wastebasket",
            "garbage can",
        ],
        C::Cup => &["cup", "teacup"],
        C::Mug => &["mug", "coffee mug"],
        C::Book => &["book", "hardback", "volume"],
        C::Laptop => &["laptop", "notebook computer", "laptop computer"],
        C::Vase => &["vase", "flower vase"],
        C::Bowl => &["bowl"],
        C::Bottle => &["bottle"],
        C::Clock => &["clock"],
        C::TableLamp => &["table lamp", "desk lamp", "bedside lamp"],
        C::SmallPlant => &["small plant", "little plant", "plant pot", "succulent"],
        C::Monitor => &["monitor", "computer screen", "display"],
        C::Keyboard => &["keyboard"],
        C::Remote => &["remote", "remote control", "tv remote"],
        C::Pillow => &["pillow", "cushion"],
        C::Toaster => &["toaster"],
        C::Kettle => &["kettle"],
        C::Microwave => &["microwave", "microwave oven"],
        C::Candle => &["candle"],
        C::PictureFrame => &[
            "picture frame",
            "photo frame",
            "framed picture",
            "framed photo",
        ],
        C::Towel => &["towel", "hand towel"],
        C::SoapDispenser => &["soap dispenser", "soap pump"],
        C::Plate => &["plate", "dinner plate"],
        C::Wall => &["wall"],
        C::Floor => &["floor"],
        C::Ceiling => &["ceiling"],
        C::DoorFrame => &["door frame", "doorframe"],
        C::Window => &["window"],
        C::Unknown => &["unknown", "object", "thing"],
    }
}

/// The classes whose names include `name` (for checks: a synonym names one class, or a class
/// whose names overlap in a word, e.g. "plant" for both plants).
pub fn class_of_name(name: &str) -> Vec<C> {
    C::ALL
        .iter()
        .copied()
        .filter(|&c| class_names(c).contains(&name))
        .collect()
}

/// Names of a room type, the vocabulary name first.
pub fn room_names(kind: RoomType) -> &'static [&'static str] {
    match kind {
        RoomType::LivingRoom => &["living room", "lounge", "sitting room", "family room"],
        RoomType::Kitchen => &["kitchen"],
        RoomType::DiningRoom => &["dining room", "dining area"],
        RoomType::Bedroom => &["bedroom", "sleeping room"],
        RoomType::Bathroom => &["bathroom", "washroom", "restroom"],
        RoomType::Hallway => &["hallway", "hall", "corridor", "passage"],
        RoomType::Office => &["office", "study", "home office", "workroom"],
        RoomType::LaundryRoom => &["laundry room", "utility room", "laundry"],
        RoomType::Closet => &["closet", "storage room", "box room"],
        RoomType::Gym => &["gym", "home gym", "workout room", "exercise room"],
        RoomType::Room => &["room", "spare room", "empty room"],
    }
}

/// What objects of a class are for, as a phrase after the name ("the kettle for boiling
/// water"): true of every object of the class, so it never claims more than the class does.
pub fn class_uses(class: C) -> &'static [&'static str] {
    match class {
        C::Bed => &["where someone sleeps", "you would sleep in"],
        C::Nightstand => &["beside the sleeping area", "for keeping things at night"],
        C::Wardrobe => &["for hanging clothes", "where clothing is stored"],
        C::Dresser => &["full of drawers", "for folded clothing"],
        C::Toilet => &["you'd flush"],
        C::Sink => &["for washing hands", "with the tap"],
        C::Bathtub => &["for bathing", "you could soak in"],
        C::Shower => &["for washing", "you'd rinse off in"],
        C::Mirror => &["you can see yourself in", "showing your reflection"],
        C::Fridge => &["where food is kept cold", "for chilled groceries"],
        C::Counter => &["for preparing meals", "where food gets chopped"],
        C::Stove => &["for cooking", "where meals are cooked"],
        C::Dishwasher => &["for dirty dishes", "that cleans crockery"],
        C::KitchenCabinet => &["for pots and pans", "where crockery lives"],
        C::Sofa => &["for lounging", "people relax on"],
        C::Armchair => &["for one person", "made for reading in"],
        C::Tv => &["for watching shows", "for films and programmes"],
        C::TvStand => &["that holds the screen", "under the screen"],
        C::CoffeeTable => &["for drinks and magazines"],
        C::DiningTable => &["where meals are eaten", "for family dinners"],
        C::Chair => &["for sitting"],
        C::Desk => &["where someone works", "for studying"],
        C::OfficeChair => &["on wheels", "that swivels"],
        C::Bookshelf => &["for books", "holding reading material"],
        C::PottedPlant => &["with green leaves", "with foliage"],
        C::FloorLamp => &["that lights the room", "giving off light"],
        C::Cabinet => &["for storage", "with doors"],
        C::SideTable => &["for setting things down"],
        C::ShoeRack => &["for footwear", "where shoes go"],
        C::CoatRack => &["for jackets", "where coats hang"],
        C::WashingMachine => &["for laundry", "that washes clothes"],
        C::Piano => &["with the keys", "for making music"],
        C::Bench => &["for sitting on"],
        C::Stool => &["without a back", "for perching on"],
        C::TrashCan => &["for rubbish", "where waste goes"],
        C::Cup | C::Mug => &["for hot drinks", "for tea or coffee"],
        C::Laptop => &["for browsing", "for emails"],
        C::Vase => &["for flowers", "for holding blooms"],
        C::Clock => &["that tells the time", "showing the hour"],
        C::TableLamp => &["for reading light"],
        C::Monitor => &["for the computer"],
        C::Toaster => &["for bread", "for toast"],
        C::Kettle => &["for boiling water"],
        C::Microwave => &["for reheating food", "for heating leftovers"],
        C::Towel => &["for drying off"],
        C::SoapDispenser => &["for soap"],
        _ => &[],
    }
}

/// The main colour of an object as linear RGB: the colour of its largest part.
fn main_rgb(o: &SceneObject) -> Option<[f32; 3]> {
    o.parts
        .iter()
        .map(|p| (part_volume(&p.shape), p.color))
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, c)| c)
}

fn part_volume(s: &Shape) -> f32 {
    match s {
        Shape::Cuboid { half_extents: h } => 8.0 * h[0] * h[1] * h[2],
        Shape::Cylinder {
            radius,
            half_height,
        } => std::f32::consts::PI * radius * radius * 2.0 * half_height,
        Shape::Sphere { radius } => 4.19 * radius * radius * radius,
        Shape::Mesh(_) => 0.0,
    }
}

/// Colour phrases for an object: its colour word, alone or with a shade read from the rendered
/// colour of its largest part ("dark blue", "pale pink"); empty when it has no colour word.
/// Only shades the RGB supports are offered.
pub fn color_phrases(o: &SceneObject) -> Vec<String> {
    let c = o.color.as_str();
    if c.is_empty() {
        return Vec::new();
    }
    let mut out = vec![c.to_string()];
    let Some(rgb) = main_rgb(o) else {
        return out;
    };
    let hi = rgb.iter().copied().fold(0.0f32, f32::max);
    let lo = rgb.iter().copied().fold(1.0f32, f32::min);
    let sat = if hi > 0.0 { (hi - lo) / hi } else { 0.0 };
    let mut add = |words: &[&str]| out.extend(words.iter().map(|w| w.to_string()));
    match c {
        "white" if hi > 0.89 => add(&["pure white", "snow-white"]),
        "white" if sat > 0.05 => add(&["off-white", "creamy white", "ivory"]),
        "white" => add(&["whitish", "pale"]),
        "black" => add(&["jet-black", "dark", "ebony"]),
        "grey" if hi < 0.37 => add(&["dark grey", "charcoal", "charcoal-grey", "slate-grey"]),
        "grey" if hi > 0.5 => add(&["light grey", "pale grey", "greyish"]),
        "grey" => add(&["mid-grey", "grey-coloured", "greyish"]),
        "silver" => add(&["silvery", "steel-grey", "silver-coloured"]),
        "gold" => add(&["golden", "gold-coloured", "brassy"]),
        "wooden" => add(&["wood-coloured", "honey-brown", "warm brown"]),
        "beige" => add(&["sandy", "cream-coloured", "light beige", "tan"]),
        "pink" => add(&["pale pink", "rosy", "pinkish"]),
        "orange" if hi < 0.7 => add(&["burnt orange", "rusty orange", "orangey"]),
        "orange" => add(&["deep orange", "tangerine", "orangey"]),
        _ if hi < 0.32 => add(match c {
            "brown" => &["dark brown", "chocolate-brown", "deep brown"],
            "green" => &["dark green", "forest-green", "deep green"],
            "blue" => &["dark blue", "navy", "navy-blue"],
            "red" => &["dark red", "maroon", "wine-red"],
            _ => &[],
        }),
        _ if hi < 0.56 => add(match c {
            "red" => &["deep red", "crimson", "brick-red", "reddish"],
            "blue" => &["deep blue", "dark blue", "navy", "bluish"],
            "green" => &["deep green", "dark green", "leafy green", "greenish"],
            "brown" => &["mid-brown", "brownish"],
            _ => &[],
        }),
        _ => add(match c {
            "red" => &["vivid red", "scarlet", "reddish", "rich red"],
            "blue" => &["royal blue", "mid-blue", "bluish", "cobalt"],
            "green" => &["mid-green", "grass-green", "greenish"],
            "yellow" if rgb[1] < 0.66 * rgb[0] => &["mustard", "mustard-yellow", "ochre"],
            "yellow" => &["golden yellow", "sunny yellow", "yellowish", "lemon-yellow"],
            "brown" => &["brownish", "light brown"],
            _ => &[],
        }),
    }
    out
}

/// Material adjectives for an object's material word (what it is made of); empty when none
/// reads naturally for its class.
pub fn material_words(o: &SceneObject) -> &'static [&'static str] {
    let upholstered = matches!(o.class, C::Sofa | C::Armchair | C::OfficeChair | C::Bench);
    match o.material.as_str() {
        "wood" if o.color != "wooden" => &["wooden", "wood", "timber"],
        "fabric" if upholstered => &["fabric", "upholstered", "cloth-covered"],
        "fabric" => &["fabric", "cloth"],
        "leather" => &["leather", "leather-covered"],
        "metal" => &["metal", "metallic", "steel"],
        "plastic" => &["plastic"],
        "ceramic" => &["ceramic", "china", "porcelain"],
        "glass" => &["glass"],
        "wax" => &["wax"],
        _ => &[],
    }
}

/// Size and shape words an object's geometry supports: height, footprint, bulk relative to
/// others of its class in the scene, and the shape of its largest part.
pub fn shape_words(o: &SceneObject, peers: &[&SceneObject]) -> Vec<&'static str> {
    let s = o.bbox.size();
    let (w, h, d) = (s.x.max(s.z), s.y, s.x.min(s.z));
    let mut out = Vec::new();
    let furniture = o.class.kind() == vlnverse_env::ClassKind::Furniture;
    if furniture && h > 1.5 {
        out.extend(["tall", "towering", "high"]);
    } else if furniture && h < 0.55 && w > 0.5 {
        out.extend(["low", "low-slung", "squat"]);
    }
    if furniture && w > 1.8 {
        out.extend(["long", "wide", "broad"]);
    } else if furniture && d > 0.0 && w / d > 2.5 && w > 0.8 {
        out.extend(["long", "narrow", "slim"]);
    } else if furniture && (w - d).abs() < 0.1 * w && w > 0.5 {
        out.extend(["square", "boxy"]);
    }
    let largest = o
        .parts
        .iter()
        .max_by(|a, b| part_volume(&a.shape).total_cmp(&part_volume(&b.shape)));
    match largest.map(|p| &p.shape) {
        Some(Shape::Cylinder { .. }) => out.extend(["round", "circular", "cylindrical"]),
        Some(Shape::Sphere { .. }) => out.extend(["round", "rounded", "ball-shaped"]),
        _ => {}
    }
    // Bulk against the other objects of its class, when there are any.
    let vol = |x: &SceneObject| {
        let s = x.bbox.size();
        s.x * s.y * s.z
    };
    let others: Vec<f32> = peers
        .iter()
        .filter(|x| x.class == o.class && x.id != o.id)
        .map(|x| vol(x))
        .collect();
    if !others.is_empty() {
        let v = vol(o);
        if others.iter().all(|&x| v > 1.3 * x) {
            out.extend(["large", "big", "bigger", "larger", "sizeable"]);
        } else if others.iter().all(|&x| v * 1.3 < x) {
            out.extend(["small", "little", "smaller", "compact"]);
        }
    }
    out
}

/// A whole number written out ("three", "twenty-four"); digits above ninety-nine.
pub fn number_word(n: u32) -> String {
    const ONES: [&str; 20] = [
        "zero",
        "one",
        "two",
        "three",
        "four",
        "five",
        "six",
        "seven",
        "eight",
        "nine",
        "ten",
        "eleven",
        "twelve",
        "thirteen",
        "fourteen",
        "fifteen",
        "sixteen",
        "seventeen",
        "eighteen",
        "nineteen",
    ];
    const TENS: [&str; 10] = [
        "", "", "twenty", "thirty", "forty", "fifty", "sixty", "seventy", "eighty", "ninety",
    ];
    match n {
        0..=19 => ONES[n as usize].to_string(),
        20..=99 if n.is_multiple_of(10) => TENS[(n / 10) as usize].to_string(),
        20..=99 => format!("{}-{}", TENS[(n / 10) as usize], ONES[(n % 10) as usize]),
        _ => n.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_name_names_its_class() {
        for &c in C::ALL {
            let names = class_names(c);
            assert_eq!(
                names[0],
                c.words(),
                "{c:?}: the vocabulary name comes first"
            );
            for n in names {
                assert_eq!(class_of_name(n), vec![c], "`{n}` names more than one class");
            }
        }
        for &k in RoomType::ALL {
            assert_eq!(room_names(k)[0], k.words());
        }
    }

    #[test]
    fn numbers_are_written_out() {
        assert_eq!(number_word(3), "three");
        assert_eq!(number_word(14), "fourteen");
        assert_eq!(number_word(40), "forty");
        assert_eq!(number_word(23), "twenty-three");
        assert_eq!(number_word(120), "120");
    }
}
