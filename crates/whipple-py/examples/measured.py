# %% [markdown]
# # A measured bicycle with its uncertainty
# BicycleParameters' Fisher (Moore 2012), shipped with whipple as the preset `fisher`: its
# values and the standard deviation of every measured parameter, to every digit of
# BicycleParameters' own data, so this runs anywhere the package is installed. whipple
# propagates the σ to the critical speeds (first order, exact derivatives) and says which
# parameter matters most. A file of your own reads the same way:
# `whipple.Bicycle.from_file("FisherBenchmark.txt")` (a file is named without the
# parameter set's suffix: `Fisher`).

# %%
import whipple

fisher = whipple.Bicycle.preset("fisher")
print(fisher)
print("source:", fisher.source)
print(f"{len(fisher.sigma)} parameters carry a σ, for example c = "
      f"{fisher.to_dict()['c']:.6g} ± {fisher.sigma['c']:.3g} m")
print(fisher.critical_speeds())

# %% Which parameter moves the weave speed most (elasticities, ∂ln v_w / ∂ln p)
s = fisher.sensitivities()
order = sorted(range(len(s.key)), key=lambda i: -abs(s.elasticity_v_w[i]))
for i in order[:5]:
    print(f"{s.key[i]:>5} ({s.symbol[i]}): dv_w/dp = {s.d_v_w[i]:+.4g} m/s per {s.unit[i] or 'unit'}, elasticity {s.elasticity_v_w[i]:+.3f}")

# %% A design change by the names a design map takes: a longer trail, in the map's units
longer = fisher.replace(trail=0.09, head_angle_deg=70.0)
print(longer.name, longer.critical_speeds())
