//! Defaults per class (mass, friction, material word), colour words, and the geometric
//! heuristics that label unmatched geometry as structure.

use vlnverse_env::{Aabb, SemanticClass};

/// Colour of geometry without a material (linear RGB).
pub const DEFAULT_COLOR: [f32; 3] = [0.6, 0.6, 0.6];

/// Default `(mass kg, friction, material word)` of a class. Structure is static and its mass is
/// not used by the simulator; it gets 0.
pub fn class_defaults(class: SemanticClass) -> (f32, f32, &'static str) {
    use SemanticClass as C;
    match class {
        C::Wall | C::Ceiling | C::DoorFrame | C::Window => (0.0, 0.7, "plaster"),
        C::Floor => (0.0, 0.8, "wood"),
        C::Bed => (60.0, 0.6, "fabric"),
        C::Sofa | C::Armchair => (45.0, 0.6, "fabric"),
        C::Wardrobe | C::Dresser | C::Bookshelf | C::KitchenCabinet | C::Cabinet => {
            (50.0, 0.5, "wood")
        }
        C::Nightstand | C::SideTable | C::TvStand | C::ShoeRack => (15.0, 0.5, "wood"),
        C::CoffeeTable | C::DiningTable | C::Desk | C::Bench => (25.0, 0.5, "wood"),
        C::Chair | C::Stool => (6.0, 0.5, "wood"),
        C::OfficeChair => (12.0, 0.4, "fabric"),
        C::Fridge | C::WashingMachine | C::Dishwasher | C::Stove => (70.0, 0.5, "metal"),
        C::Toilet | C::Sink | C::Bathtub | C::Shower => (40.0, 0.5, "ceramic"),
        C::Counter => (80.0, 0.5, "stone"),
        C::Piano => (200.0, 0.6, "wood"),
        C::Tv | C::Monitor | C::Laptop | C::Keyboard => (8.0, 0.4, "plastic"),
        C::Mirror | C::PictureFrame => (3.0, 0.4, "glass"),
        C::Rug | C::Towel | C::Pillow => (2.0, 0.8, "fabric"),
        C::PottedPlant | C::SmallPlant => (5.0, 0.6, "ceramic"),
        C::FloorLamp | C::TableLamp | C::CoatRack => (4.0, 0.5, "metal"),
        C::TrashCan => (2.0, 0.5, "plastic"),
        C::Cup | C::Mug | C::Bowl | C::Plate | C::Vase => (0.4, 0.5, "ceramic"),
        C::Bottle | C::SoapDispenser => (0.5, 0.4, "plastic"),
        C::Book => (0.8, 0.6, "paper"),
        C::Clock | C::Remote | C::Candle => (0.5, 0.5, "plastic"),
        C::Toaster | C::Kettle | C::Microwave => (3.0, 0.5, "metal"),
        C::Door => (20.0, 0.5, "wood"),
        C::FruitBowl | C::Teapot => (1.0, 0.5, "ceramic"),
        C::Pot | C::Pan => (1.5, 0.4, "metal"),
        C::CuttingBoard => (1.0, 0.6, "wood"),
        C::CoffeeMachine | C::Blender | C::Printer => (4.0, 0.5, "plastic"),
        C::DishRack => (1.0, 0.4, "metal"),
        C::TissueBox | C::BoardGame | C::Magazine => (0.4, 0.6, "paper"),
        C::Basket => (0.8, 0.6, "wicker"),
        C::Speaker | C::Phone | C::Tablet | C::Headphones | C::Hairdryer => (0.6, 0.5, "plastic"),
        C::PenHolder | C::Globe | C::Toy => (0.5, 0.5, "plastic"),
        C::JewelryBox => (0.6, 0.5, "wood"),
        C::ToiletPaper => (0.1, 0.7, "paper"),
        C::Shampoo | C::ToothbrushHolder => (0.4, 0.4, "plastic"),
        C::Shoes | C::Slippers => (0.8, 0.8, "fabric"),
        C::LaundryBasket | C::Box => (2.0, 0.6, "wicker"),
        C::Backpack | C::DogBed | C::YogaMat | C::BeanBag => (2.0, 0.8, "fabric"),
        C::UmbrellaStand | C::Dumbbells => (4.0, 0.5, "metal"),
        C::Ottoman => (10.0, 0.7, "fabric"),
        C::Chest | C::Vanity => (30.0, 0.5, "wood"),
        C::FilingCabinet => (35.0, 0.4, "metal"),
        C::WallShelf | C::TowelRack | C::Curtain => (3.0, 0.5, "wood"),
        C::Radiator | C::Heater | C::Fan => (8.0, 0.4, "metal"),
        C::Fireplace => (150.0, 0.7, "stone"),
        C::Aquarium => (60.0, 0.4, "glass"),
        C::Treadmill | C::ExerciseBike => (60.0, 0.6, "metal"),
        C::Bicycle | C::IroningBoard | C::DryingRack | C::ClothesRail => (8.0, 0.5, "metal"),
        C::Crib | C::HighChair => (12.0, 0.5, "wood"),
        C::PatioChair | C::PatioTable => (6.0, 0.5, "plastic"),
        C::Planter => (20.0, 0.7, "ceramic"),
        C::ShelvingUnit => (20.0, 0.5, "metal"),
        C::Stairs => (400.0, 0.8, "wood"),
        C::Railing => (15.0, 0.5, "metal"),
        C::Recliner => (40.0, 0.7, "fabric"),
        C::RockingChair | C::Easel | C::Ladder => (8.0, 0.5, "wood"),
        C::PoolTable => (300.0, 0.6, "wood"),
        C::PingPongTable | C::FoosballTable => (70.0, 0.5, "wood"),
        C::GrandfatherClock | C::ChinaCabinet => (60.0, 0.5, "wood"),
        C::Guitar => (3.0, 0.5, "wood"),
        C::DrumKit => (25.0, 0.5, "wood"),
        C::Statue => (80.0, 0.6, "stone"),
        C::FireExtinguisher | C::Birdcage => (5.0, 0.4, "metal"),
        C::Dryer => (60.0, 0.5, "metal"),
        C::Grill => (30.0, 0.4, "metal"),
        C::KitchenIsland => (120.0, 0.5, "wood"),
        C::ConsoleTable => (15.0, 0.5, "wood"),
        C::Column => (200.0, 0.6, "stone"),
        C::Chandelier => (10.0, 0.4, "metal"),
        C::MassageTable | C::ChaiseLounge => (25.0, 0.7, "fabric"),
        C::Hammock => (12.0, 0.7, "fabric"),
        C::Cactus | C::Urn => (8.0, 0.6, "ceramic"),
        C::Lounger => (10.0, 0.5, "wood"),
        C::WeightBench => (20.0, 0.6, "metal"),
        C::PunchingBag => (30.0, 0.7, "leather"),
        C::ProjectorScreen => (8.0, 0.5, "fabric"),
        C::Projector => (3.0, 0.5, "plastic"),
        C::PopcornMachine => (25.0, 0.5, "metal"),
        C::Jar => (0.5, 0.4, "glass"),
        C::WineRack => (15.0, 0.5, "wood"),
        C::Lockers => (40.0, 0.4, "metal"),
        C::ArcadeMachine => (90.0, 0.5, "wood"),
        C::Car => (1300.0, 0.8, "metal"),
        C::Workbench => (40.0, 0.5, "wood"),
        C::ChristmasTree => (15.0, 0.7, "plastic"),
        C::WallSconce => (1.5, 0.5, "metal"),
        C::Poster => (0.3, 0.6, "paper"),
        C::PorchSwing => (30.0, 0.5, "wood"),
        C::Doormat | C::Runner => (1.5, 0.8, "fabric"),
        C::GrandPiano => (400.0, 0.5, "wood"),
        C::HotTub => (300.0, 0.6, "plastic"),
        C::Fountain => (120.0, 0.6, "stone"),
        C::WaterCooler => (15.0, 0.5, "plastic"),
        C::Tapestry | C::Flag => (1.0, 0.6, "fabric"),
        C::RoomDivider => (10.0, 0.5, "wood"),
        C::Wreath => (0.5, 0.6, "plastic"),
        C::DeerHead | C::Dartboard => (3.0, 0.5, "wood"),
        C::Elliptical | C::RowingMachine => (50.0, 0.6, "metal"),
        C::Bar => (150.0, 0.5, "wood"),
        C::Dollhouse | C::RockingHorse => (10.0, 0.5, "wood"),
        C::AirHockeyTable => (80.0, 0.5, "wood"),
        C::PinballMachine | C::Jukebox => (100.0, 0.5, "wood"),
        C::Barrel => (40.0, 0.6, "wood"),
        C::BunkBed => (80.0, 0.6, "wood"),
        C::CatTree => (12.0, 0.7, "fabric"),
        C::VacuumCleaner => (6.0, 0.5, "plastic"),
        C::LawnMower => (30.0, 0.6, "metal"),
        C::Kayak => (20.0, 0.5, "plastic"),
        C::Telescope => (6.0, 0.5, "metal"),
        C::Sectional => (70.0, 0.6, "fabric"),
        C::Buffet => (50.0, 0.5, "wood"),
        C::CeilingFan => (7.0, 0.5, "metal"),
        C::WaterHeater => (60.0, 0.5, "metal"),
        C::MiniFridge => (25.0, 0.5, "metal"),
        C::TeddyBear => (0.8, 0.8, "fabric"),
        C::Bust => (40.0, 0.5, "stone"),
        C::Saxophone => (3.0, 0.4, "metal"),
        C::BasketballHoop => (15.0, 0.5, "plastic"),
        C::Whiteboard | C::BulletinBoard => (4.0, 0.5, "wood"),
        C::ChessTable => (15.0, 0.5, "wood"),
        C::Candelabra => (2.0, 0.5, "metal"),
        C::ExerciseBall => (1.2, 0.8, "plastic"),
        C::Sword => (2.0, 0.4, "metal"),
        C::Rocks => (60.0, 0.8, "stone"),
        C::LightSwitch | C::Outlet | C::Thermostat | C::SmokeDetector => (0.1, 0.5, "plastic"),
        C::AirVent => (0.3, 0.5, "metal"),
        C::Calendar => (0.2, 0.6, "paper"),
        C::AirConditioner => (9.0, 0.5, "plastic"),
        C::RangeHood => (12.0, 0.5, "metal"),
        C::Futon | C::Daybed => (40.0, 0.6, "fabric"),
        C::TrophyCase => (50.0, 0.5, "wood"),
        C::Amplifier => (15.0, 0.6, "plastic"),
        C::Microphone => (3.0, 0.5, "metal"),
        C::Violin => (0.5, 0.5, "wood"),
        C::Toolbox => (60.0, 0.5, "metal"),
        C::Wheelbarrow => (20.0, 0.5, "metal"),
        C::Shovel | C::Broom => (1.5, 0.5, "wood"),
        C::GardenHose => (8.0, 0.7, "plastic"),
        C::Suitcase => (5.0, 0.5, "plastic"),
        C::MopBucket => (6.0, 0.5, "plastic"),
        C::BathroomScale => (2.0, 0.6, "plastic"),
        C::Firewood => (30.0, 0.7, "wood"),
        C::SpiceRack | C::KnifeBlock => (2.0, 0.5, "wood"),
        C::SewingMachine | C::Typewriter | C::RecordPlayer => (7.0, 0.5, "metal"),
        C::Radio => (2.0, 0.5, "plastic"),
        C::Unknown => (10.0, 0.5, "unknown"),
    }
}

/// Nearest colour word of a linear RGB colour.
pub fn color_word(c: [f32; 3]) -> &'static str {
    // Compare in sRGB, where distances are closer to what people call "the same colour".
    let s = c.map(|v| {
        let v = v.clamp(0.0, 1.0);
        if v <= 0.003_130_8 {
            v * 12.92
        } else {
            1.055 * v.powf(1.0 / 2.4) - 0.055
        }
    });
    const PALETTE: &[(&str, [f32; 3])] = &[
        ("white", [0.95, 0.95, 0.95]),
        ("black", [0.08, 0.08, 0.08]),
        ("gray", [0.55, 0.55, 0.55]),
        ("red", [0.8, 0.15, 0.15]),
        ("green", [0.2, 0.6, 0.2]),
        ("blue", [0.2, 0.3, 0.8]),
        ("yellow", [0.9, 0.85, 0.2]),
        ("orange", [0.95, 0.55, 0.15]),
        ("brown", [0.5, 0.3, 0.15]),
        ("beige", [0.85, 0.78, 0.62]),
        ("pink", [0.95, 0.6, 0.7]),
        ("purple", [0.5, 0.25, 0.6]),
    ];
    let mut best = ("gray", f32::INFINITY);
    for (name, p) in PALETTE {
        let d = (0..3).map(|i| (s[i] - p[i]).powi(2)).sum::<f32>();
        if d < best.1 {
            best = (name, d);
        }
    }
    best.0
}

/// Guess the class of unlabelled geometry from its world bounding box (floor at `y = floor`):
/// thin, large and horizontal with its top at floor level -> floor; the same high up -> ceiling; tall, thin
/// and long -> wall; much larger than furniture -> wall (a building shell); else unknown.
pub fn structure_guess(b: &Aabb, floor: f32) -> SemanticClass {
    let s = b.size();
    let footprint = s.x * s.z;
    let thin_h = s.x.min(s.z);
    let long_h = s.x.max(s.z);
    if s.y < 0.3 && s.x > 1.0 && s.z > 1.0 && footprint > 2.0 {
        if (b.max[1] - floor).abs() < 0.15 {
            return SemanticClass::Floor;
        }
        if b.min[1] - floor > 1.8 {
            return SemanticClass::Ceiling;
        }
    }
    if s.y > 1.5 && b.min[1] - floor < 0.3 && thin_h < 0.35 && long_h > 0.8 {
        return SemanticClass::Wall;
    }
    if footprint > 12.0 && s.y > 1.5 {
        return SemanticClass::Wall;
    }
    SemanticClass::Unknown
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn heuristics_tell_walls_floors_and_furniture_apart() {
        let floor = Aabb::new(Vec3::new(-3.0, -0.05, -3.0), Vec3::new(3.0, 0.0, 3.0));
        assert_eq!(structure_guess(&floor, 0.0), SemanticClass::Floor);
        let ceiling = Aabb::new(Vec3::new(-3.0, 2.5, -3.0), Vec3::new(3.0, 2.6, 3.0));
        assert_eq!(structure_guess(&ceiling, 0.0), SemanticClass::Ceiling);
        let wall = Aabb::new(Vec3::new(-3.0, 0.0, 0.0), Vec3::new(3.0, 2.5, 0.15));
        assert_eq!(structure_guess(&wall, 0.0), SemanticClass::Wall);
        let table = Aabb::new(Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.2, 0.75, 0.8));
        assert_eq!(structure_guess(&table, 0.0), SemanticClass::Unknown);
    }

    #[test]
    fn colour_words() {
        assert_eq!(color_word([1.0, 1.0, 1.0]), "white");
        assert_eq!(color_word([0.0, 0.0, 0.0]), "black");
        assert_eq!(color_word([0.6, 0.01, 0.01]), "red");
    }
}
